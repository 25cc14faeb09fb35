#include "statmc/plugin_sdk/operator_spec.h"

namespace statmc {

void take_variadic_inputs(OperatorSpec& op, int min_inputs, const std::string& noun)
{
    op.inputs = kVariadicInputs;
    op.min_inputs = min_inputs;
    op.input_noun = noun;
    op.parameters.push_back(
        int_parameter("n", std::nullopt,
                      "number of " + noun + " popped; without it, the whole stack")
            .at_least(min_inputs));
}

}  // namespace statmc
