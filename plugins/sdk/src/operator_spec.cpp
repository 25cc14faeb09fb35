#include "statmc/plugin_sdk/operator_spec.h"

#include <iostream>

namespace statmc {

void RunContext::tell(const std::string& line) const
{
    if (message)
        message(line);
    else
        std::cerr << line << "\n";
}

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

std::string OperatorSpec::input_count_problem(std::size_t count) const
{
    const std::string got = ", got " + std::to_string(count);
    if (inputs == kVariadicInputs)
        return count < std::size_t(min_inputs)
                   ? "needs at least " + std::to_string(min_inputs) + " " + input_noun + got
                   : "";
    return count != std::size_t(inputs)
               ? "needs " + std::to_string(inputs) + (inputs == 1 ? " image" : " images") + got
               : "";
}

}  // namespace statmc
