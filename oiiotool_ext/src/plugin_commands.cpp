#include "statmc/tool/plugin_commands.h"

#include <iostream>

#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/plugin_catalog.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

std::size_t input_count(const statmc::OperatorSpec& op, const Invocation& inv,
                        const ToolContext& ctx)
{
    if (op.inputs != statmc::kVariadicInputs)
        return std::size_t(op.inputs);
    const std::size_t k =
        inv.modifiers.has("n") ? std::size_t(inv.modifiers.get_int("n")) : ctx.stack.size();
    if (const std::string why = op.input_count_problem(k); !why.empty())
        throw host::HostError(inv.name + ": " + why);
    return k;
}

// Calls into a module. Operators report errors on their image and never throw, but a
// third-party one may: that becomes an error naming the operator and its module.
template <class Call>
auto guarded(const statmc::OperatorSpec& op, const std::string& where, Call&& call)
{
    const std::string culprit =
        "--" + op.name + " (" + (op.module.empty() ? "the host" : op.module) + ")";
    try {
        return call();
    } catch (const std::exception& e) {
        throw host::HostError("--" + op.name + ": " + where +
                              "the operator threw, which it must not: " + e.what() + " [" +
                              culprit + "]");
    } catch (...) {
        throw host::HostError("--" + op.name + ": " + where +
                              "the operator threw a non-standard exception [" + culprit + "]");
    }
}

void run_operator(const statmc::OperatorSpec& op, ToolContext& ctx, const Invocation& inv)
{
    const std::size_t count = input_count(op, inv, ctx);
    std::vector<StackImage> popped = ctx.stack.pop(count, inv.name);
    std::vector<const OIIO::ImageBuf*> images;
    statmc::RunContext run_context;
    run_context.nthreads = ctx.nthreads;
    run_context.out = &ctx.out;
    run_context.module = op.module;
    run_context.message = [](const std::string& line) { std::cerr << line << "\n"; };
    for (const StackImage& s : popped) {
        images.push_back(&s.image());
        run_context.input_labels.push_back(s.label);
    }
    // The input as read, for the sequence to keep when it asks for its neighbours; in
    // place, the operator's own image until it writes.
    const OIIO::ImageBuf* centre = popped.empty() ? nullptr : &popped[0].image();
    if (popped.size() == 1 && popped[0].sequence) {
        run_context.sequence_frames = [&, seq = popped[0].sequence,
                                       frame = popped[0].frame](const std::vector<int>& offsets) {
            seq->remember(frame, *centre);
            return seq->around(frame, offsets, ctx.input);
        };
    }
    // One input is named in the message; several are named by the operator itself.
    const std::string where = popped.size() == 1 ? popped[0].label + ": " : "";
    StackImage result;
    if (op.run_in_place && popped.size() == 1) {
        // The popped image is the stack's own, so the operator may reuse it (statmc's
        // operators read subimage 0 and push a one-part image either way).
        OIIO::ImageBuf image = std::move(popped[0].subimages.front());
        centre = &image;
        guarded(op, where,
                [&] { return op.run_in_place(image, inv.modifiers.values(), run_context); });
        result = StackImage{std::move(image), ""};
    } else {
        result = StackImage{
            guarded(op, where, [&] { return op.run(images, inv.modifiers.values(), run_context); }),
            ""};
    }
    if (result.image().has_error())
        throw host::HostError(inv.name + ": " + where + result.image().geterror());
    result.label =
        popped.size() == 1 ? popped[0].label + " (" + op.name + ")" : inv.name + " result";
    ctx.stack.push(std::move(result));
}

}  // namespace

const std::vector<Command>& plugin_commands()
{
    static const std::vector<Command> commands = [] {
        std::vector<Command> list;
        for (const statmc::OperatorSpec& op : host::plugin_registry().operators())
            list.push_back(operator_command(op));
        return list;
    }();
    return commands;
}

Command operator_command(const statmc::OperatorSpec& op)
{
    Command c;
    c.name = "--" + op.name;
    c.summary = op.summary;
    c.modifiers = op.parameters;
    c.check = [op](const Invocation& inv) {
        if (op.check)
            if (const std::string why =
                    guarded(op, "", [&] { return op.check(inv.modifiers.values()); });
                !why.empty())
                throw host::HostError(inv.name + ": " + why);
    };
    c.run = [op](ToolContext& ctx, const Invocation& inv) { run_operator(op, ctx, inv); };
    return c;
}

}  // namespace statmc::tool
