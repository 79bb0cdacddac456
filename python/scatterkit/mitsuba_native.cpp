// scatterkit's phase functions as a native Mitsuba 3 phase plugin,
// "scatterkit_native", for Mitsuba's scalar variants: C++ built against the
// headers Mitsuba's wheel ships, sampling and evaluating through scatterkit's
// portable header (include/scatterkit_portable.h, float only, as Mitsuba's
// scalar variants compute). scatterkit.mitsuba.register_native() compiles
// it, loads it and calls scatterkit_mitsuba_register(); see that module for
// the properties.
//
// Conventions: Mitsuba's wi points away from the scattering point, so the
// direction of travel is -wi and the scattering cosine of wo is
// mu = -dot(wi, wo). Analytic models sample with the header's sample_dir
// about -wi and return weight 1 and the model's density. A table (any other
// phase function: Mie, mixtures, Fournier-Forand, ...) samples the
// library's inverse-CDF table and evaluates a density table of the model
// itself (values at mu = 1 - 2 s^2, s even in [0, 1], interpolated linearly
// in s); its weight is that density over the table's sampling density, so
// the estimate stays unbiased whatever the table's error, and the density
// table's value is the pdf for multiple importance sampling in both calls.

#include <mitsuba/core/plugin.h>
#include <mitsuba/core/properties.h>
#include <mitsuba/render/interaction.h>
#include <mitsuba/render/phase.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "scatterkit_portable.h"

NAMESPACE_BEGIN(mitsuba)

namespace {

std::vector<float> parse_floats(const std::string &s) {
    std::vector<float> out;
    std::string tok;
    std::stringstream ss(s);
    while (std::getline(ss, tok, ',')) {
        size_t used = 0;
        float v = std::stof(tok, &used);
        // A number and nothing after it but spaces ("0.5x" is refused).
        if (tok.find_first_not_of(" \t\n", used) != std::string::npos)
            Throw("scatterkit_native: \"%s\" is not a number", tok);
        out.push_back(v);
    }
    return out;
}

enum class Model { Isotropic, Hg, Rayleigh, Draine, Fog, TwoLobe, Schlick, Table };

} // namespace

template <typename Float, typename Spectrum>
class ScatterkitNative final : public PhaseFunction<Float, Spectrum> {
public:
    MI_IMPORT_BASE(PhaseFunction, m_flags, m_components)
    MI_IMPORT_TYPES(PhaseFunctionContext)
    static_assert(!dr::is_jit_v<Float>, "scatterkit_native is for Mitsuba's scalar variants");

    ScatterkitNative(const Properties &props) : Base(props) {
        std::string model(props.get<std::string_view>("model"));
        auto f = [&](const char *name) { return (float) props.get<ScalarFloat>(name); };
        int ok = 1;
        if (model == "isotropic") {
            m_model = Model::Isotropic;
        } else if (model == "henyey_greenstein") {
            m_model = Model::Hg;
            ok = skp_hg_new(f("g"), &m_hg);
        } else if (model == "rayleigh") {
            m_model = Model::Rayleigh;
        } else if (model == "draine") {
            m_model = Model::Draine;
            ok = skp_draine_new(f("g"), f("alpha"), &m_draine);
        } else if (model == "cornette_shanks") {
            m_model = Model::Draine;
            ok = skp_draine_new(f("g"), 1.0f, &m_draine);
        } else if (model == "fog") {
            m_model = Model::Fog;
            ok = skp_fog_new(f("g_hg"), f("g_d"), f("alpha"), f("w_d"), &m_fog);
        } else if (model == "two_lobe_hg") {
            m_model = Model::TwoLobe;
            ok = skp_two_lobe_new(f("g1"), f("g2"), f("w"), &m_two);
        } else if (model == "schlick") {
            m_model = Model::Schlick;
            ok = skp_schlick_new(f("k"), &m_schlick);
        } else if (model == "table") {
            m_model = Model::Table;
            m_table = parse_floats(std::string(props.get<std::string_view>("table")));
            m_density = parse_floats(std::string(props.get<std::string_view>("density")));
            ok = m_table.size() >= 4 && m_table.size() % 2 == 0 && m_density.size() >= 2;
            for (float v : m_table)
                ok = ok && std::isfinite(v);
            for (float v : m_density)
                ok = ok && std::isfinite(v) && v >= 0.0f;
            m_n = (skp_u32) (m_table.size() / 2 - 1);
        } else {
            Throw("scatterkit_native: unknown model \"%s\"", model);
        }
        if (!ok)
            Throw("scatterkit_native: parameters out of the domain of model \"%s\"", model);
        m_flags = m_model == Model::Isotropic ? +PhaseFunctionFlags::Isotropic
                                              : +PhaseFunctionFlags::Anisotropic;
        m_components.push_back(m_flags);
    }

    std::tuple<Vector3f, Spectrum, Float> sample(const PhaseFunctionContext &,
                                                 const MediumInteraction3f &mei, Float,
                                                 const Point2f &u, Mask) const override {
        skp_vec3 w = { -mei.wi.x(), -mei.wi.y(), -mei.wi.z() };
        skp_dir_sample s;
        float weight = 1.0f;
        switch (m_model) {
            case Model::Isotropic: s = skp_isotropic_sample_dir(u.x(), u.y()); break;
            case Model::Hg: s = skp_hg_sample_dir(m_hg, w, u.x(), u.y()); break;
            case Model::Rayleigh: s = skp_rayleigh_sample_dir(w, u.x(), u.y()); break;
            case Model::Draine: s = skp_draine_sample_dir(m_draine, w, u.x(), u.y()); break;
            case Model::Fog: s = skp_fog_sample_dir(m_fog, w, u.x(), u.y()); break;
            case Model::TwoLobe: s = skp_two_lobe_sample_dir(m_two, w, u.x(), u.y()); break;
            case Model::Schlick: s = skp_schlick_sample_dir(m_schlick, w, u.x(), u.y()); break;
            default: {
                float p_table;
                float mu = skp_table_sample_cos_pdf(m_table.data(), m_n, u.x(), &p_table);
                s.dir = skp_direction_about(w, mu, std::sqrt(std::max(0.0f, (1.0f - mu) * (1.0f + mu))), u.y());
                s.cos_theta = mu;
                s.pdf = density(mu);
                weight = p_table > 0.0f && std::isfinite(p_table) ? s.pdf / p_table : 0.0f;
            }
        }
        return { Vector3f(s.dir.x, s.dir.y, s.dir.z), Spectrum(weight), Float(s.pdf) };
    }

    std::pair<Spectrum, Float> eval_pdf(const PhaseFunctionContext &,
                                        const MediumInteraction3f &mei, const Vector3f &wo,
                                        Mask) const override {
        // In double: a float dot product of two unit vectors rounds by up to
        // a few ulp, which the density near a forward peak would see.
        double mu = -((double) mei.wi.x() * wo.x() + (double) mei.wi.y() * wo.y() +
                      (double) mei.wi.z() * wo.z());
        float m = (float) (mu > 1.0 ? 1.0 : (mu < -1.0 ? -1.0 : mu));
        float p;
        switch (m_model) {
            case Model::Isotropic: p = SKP_INV_4PI; break;
            case Model::Hg: p = skp_hg_pdf(m_hg, m); break;
            case Model::Rayleigh: p = skp_rayleigh_pdf(m); break;
            case Model::Draine: p = skp_draine_pdf(m_draine, m); break;
            case Model::Fog: p = skp_fog_pdf(m_fog, m); break;
            case Model::TwoLobe: p = skp_two_lobe_pdf(m_two, m); break;
            case Model::Schlick: p = skp_schlick_pdf(m_schlick, m); break;
            default: p = density(m);
        }
        return { Spectrum(p), Float(p) };
    }

    std::string to_string() const override { return "ScatterkitNative[]"; }

    MI_DECLARE_CLASS(ScatterkitNative)

private:
    /// The density table at mu = 1 - 2 s^2, s = k/(K - 1), linear in s.
    float density(float mu) const {
        double s = std::sqrt(std::max(0.0, (1.0 - (double) mu) * 0.5));
        double x = s * (double) (m_density.size() - 1);
        size_t i = (size_t) x;
        if (i >= m_density.size() - 1)
            return m_density.back();
        double t = x - (double) i;
        return (float) (m_density[i] + t * (m_density[i + 1] - m_density[i]));
    }

    Model m_model;
    skp_hg m_hg;
    skp_draine m_draine;
    skp_fog m_fog;
    skp_two_lobe m_two;
    skp_schlick m_schlick;
    std::vector<float> m_table, m_density;
    skp_u32 m_n = 0;
};

NAMESPACE_END(mitsuba)

namespace {
template <typename Float, typename Spectrum>
mitsuba::ref<mitsuba::Object> instantiate(void *, const mitsuba::Properties &props) {
    return new mitsuba::ScatterkitNative<Float, Spectrum>(props);
}
void release(void *) {}
} // namespace

/// Registers "scatterkit_native" for the scalar variants this Mitsuba has.
extern "C" MI_EXPORT void scatterkit_mitsuba_register() {
    using namespace mitsuba;
    PluginManager::instance()->register_plugin(
        "scatterkit_native", "scalar_rgb", ObjectType::PhaseFunction,
        &instantiate<float, Color<float, 3>>, &release, nullptr);
    PluginManager::instance()->register_plugin(
        "scatterkit_native", "scalar_spectral", ObjectType::PhaseFunction,
        &instantiate<float, Spectrum<float, 4>>, &release, nullptr);
}
