//! Model comparison on the FANUC R-2000iC/165F data (examples/data): the forward selection of
//! `stiffid identify --compare-models`, printed as a table.
//!
//! `cargo run --release -p stiffid --example compare_models`

use stiffid::internal::identify::compare::{compare, default_candidates};
use stiffid::internal::io::measurements;

fn main() -> stiffid::Result<()> {
    let setup = stiffid::internal::setup::builtin("fanuc-r2000ic-165f")?;
    let text = include_str!("../../../examples/data/fanuc-r2000ic-165f/measurements.csv");
    let mut file = measurements::parse(text)?;
    file.to_base_frame(&setup)?;
    let candidates = default_candidates(&setup);
    let t = std::time::Instant::now();
    let c = compare(&setup, &file.measurements, &candidates, true)?;
    let elapsed = t.elapsed();
    for (s, step) in c.steps.iter().enumerate() {
        println!("step {}", s + 1);
        for r in &step.candidates {
            println!(
                "  {:8} n={:2} in={:.3} held={:?} phys={} id={} ratio={:?}",
                r.added.as_deref().unwrap_or("-"),
                r.parameters,
                r.in_sample_explained,
                r.held_out_explained,
                r.physical,
                r.identified,
                r.noise_ratio
            );
        }
    }
    for (i, r) in c.models.iter().enumerate() {
        println!(
            "{} {:?} n={} held={:?} mse={:?} phys={} aic={:.1} bic={:.1}",
            if i == c.recommended { "*" } else { " " },
            r.springs,
            r.parameters,
            r.held_out_explained,
            r.held_out_mse,
            r.physical,
            r.aic,
            r.bic
        );
    }
    println!("nested: {:?}", c.nested);
    println!("stiffness: {:?}", c.recommended_fit.stiffness.as_slice());
    println!("elapsed {elapsed:?}");
    Ok(())
}
