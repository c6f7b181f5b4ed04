//! Writes the generated 6R robot with STL collision meshes (`tests/support/mesh_robot.rs`) and a
//! setup of it in a cell into a directory, to try the robot's own bodies from the command line:
//!
//! ```sh
//! cargo run --release -p stiffid --example mesh_robot -- /tmp/mesh
//! stiffid select --setup /tmp/mesh/cell.toml --global --report /tmp/mesh/plan --out /tmp/mesh/group.csv
//! ```

#[path = "../tests/support/mesh_robot.rs"]
mod mesh_robot;

use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let Some(dir) = std::env::args().nth(1).map(PathBuf::from) else {
        eprintln!("usage: mesh_robot DIR (a new or empty directory)");
        std::process::exit(2);
    };
    for (path, bytes) in mesh_robot::files(48) {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().expect("a file in a directory"))?;
        std::fs::write(path, bytes)?;
    }
    std::fs::write(dir.join("cell.toml"), mesh_robot::setup_toml())?;
    println!("{}", dir.join("cell.toml").display());
    Ok(())
}
