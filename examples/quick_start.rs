use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::{Error, Phase, PhaseFunction, RayleighMethod, Vec3, rayleigh};

fn main() -> Result<(), Error> {
    let hg = Phase::henyey_greenstein(0.7f32)?; // validated once, here
    let w_in = Vec3::new(0.0, 0.0, 1.0); // propagation direction
    let (w_out, pdf) = hg.sample_dir(w_in, 0.25, 0.5); // your uniforms in [0, 1]
    let mu = hg.sample_cos(0.5); // inverse CDF, monotone in u
    println!("HG: {w_out:?} with pdf {pdf:.4} per sr; median cos θ {mu:.4}");

    // Or draw the uniforms from a rand_core 0.10 generator:
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let d = rayleigh::sample_dir(RayleighMethod::Direct, w_in, &mut rng);
    println!("Rayleigh (Frisvad's direct method): {d:?}");
    Ok(())
}
