#!/usr/bin/env bash
# Regenerates the committed validation reports in reports/ with the release binary:
#   reports/data/      bench of the bundled models (data/), with one HTML page per model
#   reports/refdata/   bench of the whole reference set (../shared/refdata or $SKELFIT_REFDATA)
#   reports/studies/   tessellation and rotation studies of the bundled MakeHuman body and horse
#   reports/rig/       bench of the anatomical rig (skelfit rig) on the whole reference set, and
#                      its tessellation/rotation studies of the bundled models (reports/rig/studies/)
#   reports/real/      the anatomical rig on the real game characters of the reference set, one
#                      HTML page per character (projections of predicted vs reference joints)
#   reports/labels/    body-part labelling accuracy on the reference set
#   reports/pose/      the real characters re-posed by their artists' weights (arms 0-60 degrees
#                      below the horizontal), rigged, core joint error per pose
#   reports/scaling/   time against interior voxel count (mesh to skinned general skeleton)
#   reports/index.html links every report (skelfit report --index reports)
# Usage: tools/regenerate_reports.sh   (from anywhere; takes a few minutes)
# Set SKELFIT_SKIP_SCALING=1 to leave reports/scaling/ alone (its timings need a quiet machine).
set -euo pipefail
cd "$(dirname "$0")/.."
REFDATA="${SKELFIT_REFDATA:-../shared/refdata}"
METHOD="${SKELFIT_METHOD:-general}"
cargo build --release --quiet
BIN="${CARGO_TARGET_DIR:-target}/release/skelfit"

"$BIN" bench data --rig game_engine --method "$METHOD" --out reports/data --html --model-pages

for model in humanoid/mh_neutral_default:rig_game_engine.json quadruped/quaternius_horse:rig_gltf.json; do
  dir="data/${model%%:*}"
  out="reports/studies/$(basename "$dir")"
  "$BIN" study tessellation "$dir/mesh.obj" --reference "$dir/${model##*:}" --method "$METHOD" \
    --levels 0.1,0.25,0.5,1,2 --out "$out" --html
  "$BIN" study rotation "$dir/mesh.obj" --reference "$dir/${model##*:}" --method "$METHOD" \
    --n 8 --out "$out" --html
  rig_out="reports/rig/studies/$(basename "$dir")"
  "$BIN" study tessellation "$dir/mesh.obj" --reference "$dir/${model##*:}" --method anatomical \
    --levels 0.1,0.25,0.5,1,2 --out "$rig_out" --html
  "$BIN" study rotation "$dir/mesh.obj" --reference "$dir/${model##*:}" --method anatomical \
    --n 8 --out "$rig_out" --html
done

if [ -f "$REFDATA/README.md" ]; then
  "$BIN" bench "$REFDATA" --rig game_engine --method "$METHOD" --out reports/refdata --html
  "$BIN" bench "$REFDATA" --rig game_engine --method anatomical --out reports/rig --html
  "$BIN" bench "$REFDATA" --rig game_engine --method anatomical --select real --out reports/real --html --model-pages
  "$BIN" label --table "$REFDATA" -o reports/labels
  cargo run --release --quiet --example pose_study -- "$REFDATA" reports/pose
else
  echo "reference data not found at $REFDATA (set SKELFIT_REFDATA): reports/refdata not regenerated" >&2
fi

if [ -z "${SKELFIT_SKIP_SCALING:-}" ]; then
  cargo run --release --quiet --example scaling -- --out reports/scaling
fi

# reports/index.html: every report above, each with the verdict line its page opens with.
"$BIN" report --index reports -o reports/index.html --title "skelfit reports"
