#include "statmc/denoise/denoise_image_options.h"

#include <algorithm>
#include <charconv>

#include <OpenImageIO/strutil.h>

#include "statmc/layers/renderer_presets.h"

namespace statmc {

std::string radii_text(const std::vector<int>& radii) { return OIIO::Strutil::join(radii, ","); }

std::optional<std::vector<int>> radii_from_text(const std::string& text)
{
    std::vector<int> radii;
    if (text.empty())
        return radii;
    for (const std::string& item : OIIO::Strutil::splits(text, ",")) {
        int r = 0;
        const char* end = item.data() + item.size();
        const auto [ptr, ec] = std::from_chars(item.data(), end, r);
        if (item.empty() || ec != std::errc() || ptr != end)
            return std::nullopt;
        radii.push_back(r);
    }
    return radii;
}

std::string DenoiseImageOptions::validate() const
{
    if (std::string why = filter.validate(); !why.empty())
        return why;
    if (std::string why = temporal.validate(); !why.empty())
        return why;
    if (const auto& choices = layers::renderer_preset_choices();
        std::find(choices.begin(), choices.end(), from) == choices.end())
        return "from must be auto or a renderer preset, got '" + from + "'";
    if (guides.albedo != GuideUse::Off && guides.albedo_layer.empty())
        return "the albedo guide needs a layer name";
    if (guides.normal != GuideUse::Off && guides.normal_layer.empty())
        return "the normal guide needs a layer name";
    if (variance_radius < 0 || variance_radius > 100)
        return "variance_radius must be in [0, 100], got " + std::to_string(variance_radius);
    // Each bound as the parameter table states it (plugin.cpp): [0, 0.5].
    if (!(harm_alpha >= 0 && harm_alpha <= 0.5))
        return "do_no_harm must be in [0, 0.5], got " + std::to_string(harm_alpha);
    if (!(ici_alpha >= 0 && ici_alpha <= 0.5))
        return "ici must be in [0, 0.5], got " + std::to_string(ici_alpha);
    for (std::size_t k = 0; k < ici_radii.size(); ++k)
        if (ici_radii[k] < 1 || ici_radii[k] > 100 || (k > 0 && ici_radii[k] <= ici_radii[k - 1]))
            return "ici_radii must ascend, each in [1, 100], got " + radii_text(ici_radii);
    if (!(explained_alpha >= 0 && explained_alpha <= 0.5))
        return "explained_variance must be in [0, 0.5], got " + std::to_string(explained_alpha);
    if (!(variance_prior_dof >= 0 && variance_prior_dof <= 1000))
        return "variance_dof must be in [0, 1000], got " + std::to_string(variance_prior_dof);
    if (context_radius < 0 || context_radius > 5)
        return "context must be in [0, 5], got " + std::to_string(context_radius);
    if (!(variance_prior_alpha >= 0 && variance_prior_alpha <= 0.5))
        return "variance_prior_alpha must be in [0, 0.5], got " +
               std::to_string(variance_prior_alpha);
    if (std::find(aovs.begin(), aovs.end(), aov) != aovs.end())
        return "aovs lists '" + (aov.empty() ? std::string("beauty") : aov) +
               "', which aov denoises already";
    for (std::size_t k = 0; k < aovs.size(); ++k)
        if (std::find(aovs.begin(), aovs.begin() + k, aovs[k]) != aovs.begin() + k)
            return "aovs lists '" + aovs[k] + "' twice";
    if (joint) {
        if (aovs.empty())
            return "joint needs the AOVs to share the membership with (aovs=diffuse,specular)";
        // Each of these changes one AOV's values or statistics alone: the sum would break.
        if (temporal.frames > 0 || harm_alpha > 0 || variance_radius > 0 || explained_alpha > 0 ||
            diagnostics)
            return "joint cannot be combined yet with temporal, do_no_harm, variance_radius, "
                   "explained_variance or diagnostics";
        if (ici_alpha > 0 && !optional_stages)
            return "joint and ici cannot be combined (the ladder's radii would differ per AOV)";
    }
    if (ici_alpha > 0 && diagnostics && !optional_stages)
        return "ici and diagnostics cannot be combined yet (the radius differs per pixel)";
    return {};
}

DenoiseImageOptions DenoiseImageOptions::classic()
{
    DenoiseImageOptions o;
    o.ici_alpha = 0;
    o.variance_prior_dof = 0;
    o.variance_prior_alpha = 0;
    o.variance_test = true;
    o.context_radius = 0;
    o.filter.guide_noise = false;
    return o;
}

DenoiseImageOptions DenoiseImageOptions::paper()
{
    DenoiseImageOptions o = classic();
    o.filter = DenoiseOptions::paper();
    return o;
}

}  // namespace statmc
