//! A game loop as small as a game's first `cargo run` with ocean-fft: the default ocean, a
//! few frames and a boat's height. Built in a game's dev profile (see Cargo.toml).

fn main() -> Result<(), ocean_fft::Error> {
    let spectrum = ocean_fft::Spectrum::jonswap(10.0, 100_000.0)?;
    let config = ocean_fft::OceanConfig {
        size: 64,
        ..ocean_fft::OceanConfig::default()
    };
    let mut ocean = ocean_fft::OceanState::new(spectrum, config)?;
    let mut heights = [0.0f32; 16];
    let points: Vec<[f64; 2]> = (0..16).map(|i| [f64::from(i) * 3.0, -40.0]).collect();
    for _frame in 0..3 {
        ocean.step(1.0 / 60.0)?;
        ocean.water().heights_at(&points, &mut heights)?;
    }
    println!("boat at {:.3} m", ocean.water().height_at(12.0, -40.0)?);
    Ok(())
}
