#[path = "../tests/common/dd.rs"]
mod dd;
use scatterkit::{Phase, PhaseFunction};
fn main() {
    let mut us: Vec<f64> = (0..=512).map(|i| i as f64 / 512.0).collect();
    for k in [1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01] {
        us.push(k);
        us.push(1.0 - k);
    }
    let gs = [
        -0.999, -0.99, -0.9, -0.5, -0.1, -1e-3, 0.0, 1e-3, 0.1, 0.5, 0.9, 0.99, 0.999,
    ];
    let ws = [0.0, 1e-3, 0.1, 0.5, 0.9, 0.999, 1.0];
    let (mut w64, mut w32) = (0.0f64, 0.0f64);
    let mut worst = (0.0, 0.0, 0.0);
    for &g1 in &gs {
        for &g2 in &gs {
            for &w in &ws {
                let p = Phase::<f64>::fog(g1, g2, 0.0, w).unwrap();
                let p32 = Phase::<f32>::fog(g1 as f32, g2 as f32, 0.0, w as f32).unwrap();
                let t = |x: f64| x as f32 as f64;
                for &u in &us {
                    let exact = dd::fog_inverse(g1, g2, 0.0, w, u);
                    let e = (p.sample_cos(u) - exact).abs();
                    if e > w64 {
                        w64 = e;
                        worst = (g1, g2, w);
                    }
                    let u32 = u as f32;
                    let ex32 = dd::fog_inverse(t(g1), t(g2), 0.0, t(w), u32 as f64);
                    w32 = w32.max((p32.sample_cos(u32) as f64 - ex32).abs());
                }
            }
        }
    }
    println!("two-lobe HG via fog alpha=0: max err f64 {w64:.2e} at {worst:?}, f32 {w32:.2e}");
}
