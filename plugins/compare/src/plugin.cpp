// compare: error metrics of an image against a reference, as a statmc plugin.
// The parameter table is `statmc --help compare`, generated from the specs below.
// Pops the reference (top) and the image (below it); prints one row per metric (RMSE,
// MAE, relMSE, SSIM, DSSIM) and pushes the per-pixel absolute error image, which carries
// them as statmc:compare:<metric> (double) attributes.
#include <array>
#include <iomanip>
#include <ostream>

#include "statmc/compare/compare.h"
#include "statmc/layers/exr_files.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

std::array<std::pair<const char*, double>, 5> metric_rows(const statmc::CompareMetrics& m)
{
    return {{{"RMSE", m.rmse}, {"MAE", m.mae}, {"relMSE", m.relmse}, {"SSIM", m.ssim},
             {"DSSIM", m.dssim}}};
}

void print_table(std::ostream& out, const statmc::CompareMetrics& m, const std::string& image,
                 const std::string& reference)
{
    out << "compare: " << image << " against " << reference << "\n";
    for (const auto& [name, value] : metric_rows(m))
        out << "  " << std::left << std::setw(8) << name << std::setprecision(6) << value << "\n";
}

OIIO::ImageBuf run(const std::vector<const OIIO::ImageBuf*>& inputs,
                   const statmc::ParameterValues& p, const statmc::RunContext& ctx)
{
    statmc::CompareOptions options;
    options.relmse_epsilon = p.get_float("epsilon", options.relmse_epsilon);
    options.display =
        statmc::DisplayOptions{statmc::display_config(p.get_string("config"), ctx.module),
                               p.get_string("display"), p.get_string("view")};
    statmc::CompareMetrics metrics;
    OIIO::ImageBuf error;
    if (!statmc::compare(metrics, error, *inputs[0], *inputs[1], options, ctx.nthreads))
        return error;
    if (ctx.out)
        print_table(*ctx.out, metrics, ctx.input_labels.at(0), ctx.input_labels.at(1));
    // The numbers travel with the error image too, for hosts that read them (Python).
    for (const auto& [name, value] : metric_rows(metrics))
        error.specmod().attribute(std::string("statmc:compare:") + name, OIIO::TypeDesc::DOUBLE,
                                  &value);
    if (const std::string path = p.get_string("errorimage"); !path.empty()) {
        try {
            statmc::layers::write_image_file(error, path);
        } catch (const std::exception& e) {
            error.errorfmt("{}", e.what());
        }
    }
    return error;
}

void register_compare(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "compare";
    op.summary = "Print RMSE, MAE, relMSE, SSIM and DSSIM of an image against a reference "
                 "(top); push |image - reference|";
    op.help = "RMSE, MAE and relMSE (Rousselle et al. 2011) are means over pixels and R,G,B "
              "of the scene-linear values; SSIM (Wang et al. 2004; 11x11 Gaussian window, "
              "sigma 1.5) is on the luminance of the images shown through an OCIO view "
              "(as --display) and clamped to [0, 1].";
    op.parameters = {
        statmc::float_parameter("epsilon", 0.01, "epsilon of relMSE").above(0),
        statmc::string_parameter("errorimage", "", "also write the absolute error image here")
            .written_as("file"),
        statmc::string_parameter("view", "",
                                 "OCIO view SSIM sees the images through "
                                 "(default: the display's, sRGB in statmc's config)"),
        statmc::string_parameter("display", "", "OCIO display (default: the config's)"),
        statmc::string_parameter("config", "", "OCIO config (default: $OCIO, else statmc's own)"),
    };
    op.inputs = 2;
    op.run = run;
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_compare)
