"""Finding and running the skelfit binary, and reading what it says."""

import os
import shutil
import subprocess

import bpy

ADDON = __package__


class SkelfitPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    binary: bpy.props.StringProperty(
        name="skelfit binary",
        description="Path of the skelfit executable (empty: $SKELFIT_BIN, then PATH)",
        subtype="FILE_PATH",
        default="",
    )
    timeout: bpy.props.IntProperty(
        name="Time limit (s)",
        description="Stop skelfit after this many seconds",
        default=600,
        min=10,
    )

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "binary")
        layout.prop(self, "timeout")
        found, where = find_binary(context)
        layout.label(text=f"Using {found} ({where})" if found else where)


def preferences(context):
    addon = context.preferences.addons.get(ADDON)
    return addon.preferences if addon else None


def find_binary(context):
    """(path, where it came from), or (None, what to do) when no skelfit binary is found."""
    prefs = preferences(context)
    configured = bpy.path.abspath(prefs.binary) if prefs and prefs.binary else ""
    if configured:
        if os.path.isfile(configured) and os.access(configured, os.X_OK):
            return configured, "add-on preference"
        return None, f"the skelfit binary set in the add-on preferences is not an executable file: {configured}"
    env = os.environ.get("SKELFIT_BIN", "")
    if env:
        if os.path.isfile(env) and os.access(env, os.X_OK):
            return env, "$SKELFIT_BIN"
        return None, f"$SKELFIT_BIN is not an executable file: {env}"
    on_path = shutil.which("skelfit")
    if on_path:
        return on_path, "PATH"
    return None, (
        "skelfit binary not found: set it in Preferences > Add-ons > skelfit, "
        "or set $SKELFIT_BIN, or put skelfit on PATH"
    )


class Run:
    """A finished skelfit run: exit code, stdout lines and the classified stderr lines."""

    def __init__(self, code, stdout, stderr):
        self.code = code
        self.stdout = [line for line in stdout.splitlines() if line.strip()]
        self.errors = []
        self.warnings = []
        self.other = []
        for line in stderr.splitlines():
            if line.startswith("skelfit: error:"):
                self.errors.append(line[len("skelfit: error:"):].strip())
            elif line.startswith("skelfit: warning:"):
                self.warnings.append(line[len("skelfit: warning:"):].strip())
            elif line.startswith("skelfit: "):  # e.g. "skelfit: missing: arm R"
                self.warnings.append(line[len("skelfit: "):].strip())
            elif line.strip() and "\r" not in line:  # progress spinners rewrite one line
                self.other.append(line.strip())

    @property
    def ok(self):
        return self.code == 0

    def failure(self):
        """One line saying why the run failed."""
        if self.errors:
            return "skelfit: " + "; ".join(self.errors)
        tail = "; ".join(self.other[-3:])
        return f"skelfit failed with exit code {self.code}" + (f": {tail}" if tail else "")


def run(context, binary, args):
    """Runs ``binary args`` and returns a ``Run``; raises ``RuntimeError`` when it cannot start."""
    prefs = preferences(context)
    timeout = prefs.timeout if prefs else 600
    try:
        done = subprocess.run(
            [binary, *args],
            capture_output=True,
            text=True,
            timeout=timeout,
            stdin=subprocess.DEVNULL,
        )
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"skelfit did not finish within {timeout} s (add-on preference)")
    except OSError as error:
        raise RuntimeError(f"cannot run {binary}: {error}")
    return Run(done.returncode, done.stdout, done.stderr)
