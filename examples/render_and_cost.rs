//! Render a scene against the exact reference and cost it on an
//! architecture file:
//! `cargo run --release --example render_and_cost -- table arch/mobile-tbdr.toml`.

use umbra::sim::{Algorithm, Arch, Limits, RenderConfig, Scene, TruthSource};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let scene = args.next().unwrap_or_else(|| "table-and-sphere".to_owned());
    let arch = args.next().unwrap_or_else(|| "arch/mobile-tbdr.toml".to_owned());
    let limits = Limits::DEFAULT;
    let scene = Scene::open(&scene, &limits)?;
    let arch = Arch::open(&arch, &limits)?;
    // Williams' first depth at a bias of 0.002, everything else the default.
    // Checked once against the scene and the limits; the render and the
    // costing take the checked job.
    let config = RenderConfig { algorithm: Algorithm::First, bias: 0.002, ..RenderConfig::DEFAULT };
    let job = config.check(&scene, &limits)?;

    let render = umbra::sim::render(&job, TruthSource::Quiet)?;
    let m = &render.metrics;
    println!("{}: {}", scene.name, config.describe());
    println!(
        "  {:.3} % misclassified: {} acne, {} detachment, {} leaks; {} aliasing, {} penumbra",
        m.misclassified_percent, m.acne, m.detachment, m.leaks, m.aliasing, m.penumbra
    );

    let cost = umbra::sim::cost(&job, &arch)?;
    println!(
        "  on {}: {:.0} cycles, {:.3} ms, {} DRAM bytes, light pass bound by {}, camera pass by {}",
        arch.name,
        cost.cycles(),
        cost.seconds() * 1e3,
        cost.bytes(),
        cost.light.bottleneck().name(),
        cost.camera.bottleneck().name()
    );
    Ok(())
}
