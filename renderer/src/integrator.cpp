#include "integrator.h"

#include <algorithm>
#include <cmath>

#include "bsdf.h"

namespace statmc::render {

Rgb PathIntegrator::radiance(const Ray& camera_ray, Sampler& sampler, GuideSample& guide, PathRecord* record) const
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
    float bsdf_pdf = 0;  // solid-angle pdf of the BSDF sample that produced `ray`
    Vec3 prev_p;
    const Lights& lights = scene_.lights();

    for (int bounce = 0;; ++bounce) {
        const auto hit = scene_.intersect(ray);
        if (!hit)
            break;  // no environment light in the supported subset
        const Vec3 wo = -ray.direction;
        if (record)
            record->throughput.push_back(beta);
        if (bounce == 0)
            guide.depth = hit->t;

        // Emission seen by this ray: in full after the camera or a specular bounce (no
        // light sample could have found it), else MIS-weighted against light sampling.
        if (hit->emitter >= 0) {
            const Emitter& e = lights.emitter(hit->emitter);
            const Rgb Le = e.emitted(hit->ng, wo);
            if (!Le.is_black()) {
                if (bounce == 0 || specular_bounce) {
                    contribute(bounce, PathRecord::Technique::Emission, 1.f, beta * Le);
                } else {
                    // Direct lighting of the previous vertex, found by its BSDF sample.
                    const float light_pdf = lights.pdf(prev_p, hit->emitter, hit->p, hit->ng);
                    const float w = power_heuristic(bsdf_pdf, light_pdf);
                    contribute(bounce - 1, PathRecord::Technique::Bsdf, w, beta * Le * w);
                }
            }
        }
        if (bounce >= settings_.maxdepth)
            break;

        const Bsdf bsdf = material_bsdf(scene_.material(hit->material), hit->ns, hit->ng, hit->dpdu, hit->u, hit->v);
        if (!guide_done && !bsdf.is_specular()) {
            guide.albedo = beta * bsdf.albedo();
            guide.normal = face_forward(hit->ns, wo);
            guide_done = true;
        }

        // Next-event estimation.
        if (!bsdf.is_specular() && !lights.empty()) {
            const float us = sampler.get1d(), u1 = sampler.get1d(), u2 = sampler.get1d();
            const auto ls = lights.sample(hit->p, us, u1, u2);
            if (ls && ls->pdf > 0 && !ls->radiance.is_black()) {
                const Rgb f = bsdf.f(wo, ls->wi) * std::abs(dot(hit->ns, ls->wi));
                if (!f.is_black()) {
                    const Vec3 o = Scene::offset_origin(hit->p, hit->ng, ls->wi);
                    const float tmax = length(hit->p + ls->wi * ls->distance - o) * (1.f - 1e-3f);
                    if (!scene_.occluded(o, ls->wi, tmax)) {
                        const float w = power_heuristic(ls->pdf, bsdf.pdf(wo, ls->wi));
                        contribute(bounce, PathRecord::Technique::Light, w, beta * f * ls->radiance * (w / ls->pdf));
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
        specular_bounce = bs->specular;
        bsdf_pdf = bs->pdf;
        prev_p = hit->p;

        if (bounce > settings_.rr_start_bounce) {
            const float q = std::max(0.05f, 1.f - beta.max_component());
            if (sampler.get1d() < q)
                break;
            beta *= 1.f / (1.f - q);
        }
        ray = {Scene::offset_origin(hit->p, hit->ng, bs->wi), bs->wi};
    }
    return L;
}

}  // namespace statmc::render
