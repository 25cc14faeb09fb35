#include "statmc/denoise/denoise_image_options.h"

#include <algorithm>

#include "statmc/layers/renderer_presets.h"

namespace statmc {

DenoiseImageOptions DenoiseImageOptions::of(Method method)
{
    const MethodSettings settings = method_settings(method);
    DenoiseImageOptions o;
    o.filter = settings.filter;
    o.stages = settings.stages;
    return o;
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
        if (temporal.frames > 0 || diagnostics)
            return "joint cannot be combined yet with temporal or diagnostics";
    }
    return {};
}

}  // namespace statmc
