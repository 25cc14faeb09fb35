// The named methods (docs/method.md §11): a user chooses one, and the product's parameters
// over it; each method owns the settings of the stages it runs around the filter.
#pragma once

#include "statmc/core/denoise_options.h"
#include "statmc/core/radius_ladder.h"

namespace statmc {

enum class Method {
    Default,  ///< classic, with each pixel at its own radius (the ICI ladder) and the context test
    Classic,  ///< the 2024 filter with the firefly guard
    Paper,    ///< Sakai et al. 2024 bit for bit
};

/// What a method runs around the filter. Not product parameters: the evaluation's
/// ablations vary them, users choose a method.
struct MethodStages {
    /// Each pixel at its own radius by the ICI ladder (radius_ladder.h), whose intervals
    /// read variances moderated towards the agreeing neighbours' (ladder.variance).
    bool radius_ladder = false;
    RadiusLadderOptions ladder;
    /// > 0: a neighbour joins only where the box means of this radius agree too
    /// (context_channel.h).
    int context_radius = 0;
};

struct MethodSettings {
    DenoiseOptions filter;  ///< the filter's defaults under the method
    MethodStages stages;
};

/// The settings `method` stands for.
MethodSettings method_settings(Method method);

}  // namespace statmc
