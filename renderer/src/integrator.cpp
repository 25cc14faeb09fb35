#include "statmc/render/integrator.h"

#include <algorithm>
#include <cmath>

#include "statmc/render/bsdf.h"

namespace statmc::render {

float PathIntegrator::survival(int bounce, const Rgb& beta, const Rgb& rr_beta,
                               const PixelEstimates* estimates) const
{
    if (settings_.roulette.mode == RouletteMode::Acrr && estimates && estimates->has_luminance())
        if (const auto p = acrr_survival(beta.max_component(), estimates->luminance(bounce + 1),
                                         estimates->luminance(0)))
            return *p;
    return classic_survival(rr_beta);
}

TechniqueChoice PathIntegrator::techniques(int bounce, const PixelEstimates* estimates) const
{
    if (settings_.mis.mode != MisMode::Selective || !estimates || !estimates->has_wins() ||
        bounce >= estimates->layout->mis_bounces)
        return {};
    return choose_techniques(estimates->light_wins(bounce), estimates->bsdf_wins(bounce),
                             settings_.mis.threshold);
}

Rgb PathIntegrator::radiance(const Ray& camera_ray, Sampler& sampler, GuideSample& guide,
                             PathRecord* record, const PixelEstimates* estimates) const
{
    Rgb L, beta{1.f};
    if (record)
        record->clear();
    auto contribute = [&](int bounce, PathRecord::Technique technique, float weight, Rgb value) {
        L += value;
        if (record)
            record->contributions.push_back({bounce, technique, weight, value});
    };
    Ray ray = camera_ray;
    bool specular_bounce = false;
    bool guide_done = false;
    float bsdf_pdf = 0;           // solid-angle pdf of the BSDF sample that produced `ray`
    TechniqueChoice prev_choice;  // the techniques of the vertex that sampled `ray`
    float roulette_weight = 1;    // Π 1/p so far, for the record
    float eta_scale = 1;          // 1 / Π radiance_scale: β · eta_scale is pbrt-v3's rrBeta
    Vec3 prev_p;
    const Lights& lights = scene_.lights();

    for (int bounce = 0;; ++bounce) {
        const auto hit = scene_.intersect(ray);
        if (!hit)
            break;  // no environment light in the supported subset
        const Vec3 wo = -ray.direction;
        if (record) {
            record->throughput.push_back(beta);
            record->roulette_weight.push_back(roulette_weight);
        }
        if (bounce == 0) {
            guide.depth = hit->t;
            guide.first_hit = hit->p;
            guide.hit = true;
        }

        // Emission seen by this ray: in full after the camera or a specular bounce (no
        // light sample could have found it), else MIS-weighted against light sampling.
        if (hit->emitter >= 0) {
            const Emitter& e = lights.emitter(hit->emitter);
            const Rgb Le = e.emitted(hit->ng, wo);
            if (!Le.is_black()) {
                if (bounce == 0 || specular_bounce) {
                    contribute(bounce, PathRecord::Technique::Emission, 1.f, beta * Le);
                } else if (prev_choice.bsdf) {
                    // Direct lighting of the previous vertex, found by its BSDF sample.
                    const float light_pdf = lights.pdf(prev_p, hit->emitter, hit->p, hit->ng);
                    const float w = prev_choice.bsdf_weight(bsdf_pdf, light_pdf);
                    contribute(bounce - 1, PathRecord::Technique::Bsdf,
                               power_heuristic(bsdf_pdf, light_pdf), beta * Le * w);
                } else if (record) {
                    // SMIS skipped BSDF sampling: nothing is added, but the would-be weight
                    // still counts a win, so that the technique can come back.
                    const float light_pdf = lights.pdf(prev_p, hit->emitter, hit->p, hit->ng);
                    contribute(bounce - 1, PathRecord::Technique::Bsdf,
                               power_heuristic(bsdf_pdf, light_pdf), Rgb{});
                }
            }
        }
        if (bounce >= settings_.maxdepth)
            break;

        const Bsdf bsdf = material_bsdf(scene_.material(hit->material), hit->ns, hit->ng, hit->dpdu,
                                        hit->u, hit->v);
        if (!guide_done && !bsdf.is_specular()) {
            guide.albedo = beta * bsdf.albedo();
            guide.normal = face_forward(hit->ns, wo);
            guide_done = true;
        }

        // Next-event estimation.
        const TechniqueChoice choice = techniques(bounce, estimates);
        if (choice.light && !bsdf.is_specular() && !lights.empty()) {
            const float us = sampler.get1d(), u1 = sampler.get1d(), u2 = sampler.get1d();
            const auto ls = lights.sample(hit->p, us, u1, u2);
            if (ls && ls->pdf > 0 && !ls->radiance.is_black()) {
                const Rgb f = bsdf.f(wo, ls->wi) * std::abs(dot(hit->ns, ls->wi));
                if (!f.is_black()) {
                    const Vec3 o = Scene::offset_origin(hit->p, hit->ng, ls->wi);
                    const float tmax = length(hit->p + ls->wi * ls->distance - o) * (1.f - 1e-3f);
                    if (!scene_.occluded(o, ls->wi, tmax)) {
                        const float pdf_b = bsdf.pdf(wo, ls->wi);
                        const float w = choice.light_weight(ls->pdf, pdf_b);
                        contribute(bounce, PathRecord::Technique::Light,
                                   power_heuristic(ls->pdf, pdf_b),
                                   beta * f * ls->radiance * (w / ls->pdf));
                    }
                }
            }
        }

        // Continue the path by sampling the BSDF.
        const float u1 = sampler.get1d(), u2 = sampler.get1d(), uc = sampler.get1d();
        const auto bs = bsdf.sample(wo, u1, u2, uc);
        if (!bs || bs->weight.is_black())
            break;
        beta *= bs->weight;
        eta_scale /= bs->radiance_scale;
        specular_bounce = bs->specular;
        bsdf_pdf = bs->pdf;
        prev_p = hit->p;
        prev_choice = choice;

        if (bounce >= settings_.roulette.start_bounce) {
            const float p = survival(bounce, beta, beta * eta_scale, estimates);
            if (p < 1.f) {
                if (sampler.get1d() >= p)
                    break;
                beta *= 1.f / p;
                roulette_weight *= 1.f / p;
            }
        }
        ray = {Scene::offset_origin(hit->p, hit->ng, bs->wi), bs->wi};
    }
    return L;
}

}  // namespace statmc::render
