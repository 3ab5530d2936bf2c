use skelfit::pipeline::{rig, RigOptions};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let mesh = skelfit::mesh::load(std::path::Path::new(&path)).unwrap();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    for p in &r.labelling.parts {
        println!("{:?} {:?} {:?} attach {:.3?} distal {:.3?}", p.label, p.side, p.limb_pair, p.attachment.to_array(), p.distal.to_array());
    }
    for l in &r.input.limbs {
        println!("limb {:?} {:?} attach {:.3?} first {:.3?} r0 {:.3} n {}", l.kind, l.side, l.attach.to_array(), l.path[0].to_array(), l.radii[0], l.path.len());
        let rs: Vec<String> = l.path.iter().zip(&l.radii).step_by(3).map(|(p, r)| format!("({:.2},{:.2},{:.2}|{:.3})", p.x, p.y, p.z, r)).collect();
        println!("   {}", rs.join(" "));
    }
    let a = &r.input.axial;
    let rs: Vec<String> = a.points.iter().zip(&a.radii).step_by(4).map(|(p, r)| format!("({:.2},{:.2},{:.2}|{:.3})", p.x, p.y, p.z, r)).collect();
    println!("axial {}", rs.join(" "));
}
