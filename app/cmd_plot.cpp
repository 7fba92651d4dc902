// `shudder plot FILE --what KIND -o OUT.png|svg`: dispatch to report/plots (which reads the file,
// builds the plot and draws it through gnuplot).
#include <iostream>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/input_error.hpp"
#include "report/plots.hpp"

namespace shudder::app {

int plot_command(const PlotOptions& opt) {
  return guarded(opt.file, "plot", [&]() -> int {
    const auto kind = report::parse_plot_kind(opt.what);
    if (!kind)
      throw io::InputError("--what", 0, "",
                           "unknown plot '" + opt.what +
                               "'; use one of torque, temperature, spectrum, spectrogram, "
                               "stability_map, sweep");
    report::plot_file(opt.file, *kind, opt.output);
    std::cout << "Plot: " << opt.output << "\n";
    return 0;
  });
}

}  // namespace shudder::app
