use scatterkit::PhaseFunction;
use scatterkit::phase::HenyeyGreenstein;
use scatterkit::portable as p;
fn main() {
    let mut worst_all = (0.0f64, 0.0f32, 0.0f32, 0.0f64);
    let mut ws = 0.0f64;
    for i in 0..=400 {
        let g = (i as f32 / 400.0) * 0.999 * if i % 2 == 0 { 1.0 } else { -1.0 };
        let h = HenyeyGreenstein::<f64>::new(g as f64).unwrap();
        let hp = p::Hg::new(g).unwrap();
        for k in (0..=(1u32 << 24)).step_by(61) {
            let u = k as f32 / 16777216.0;
            let want = h.sample_cos(u as f64);
            let e = (p::hg_sample_cos(&hp, u) as f64 - want).abs();
            if e > worst_all.0 {
                worst_all = (e, g, u, want);
            }
            let (_, s, _) = p::hg_sample_cos_sin(&hp, u);
            let sw = (1.0 - want * want).max(0.0).sqrt();
            if sw > 1e-3 {
                ws = ws.max(((s as f64 - sw) / sw).abs());
            }
        }
    }
    println!(
        "worst {:.3e} at g {} u {} mu {}; sin rel {ws:.3e}",
        worst_all.0, worst_all.1, worst_all.2, worst_all.3
    );
}
