// planet bench --plot: the embedded tools/plot_frame_times.py run by a Python 3 with
// matplotlib, the benchmark's CSV on its standard input, the PNG on its standard output.
// Drawing it in C++ would need axes, tick labels, a legend and a font rasteriser; matplotlib is
// one Debian package (python3-matplotlib, in tools/setup.sh) and the script also runs on its
// own on a saved CSV.
#pragma once

#include <string>

namespace planet::cli {

// A Python that imports matplotlib: $PLANET_PYTHON if set, else python3 from PATH, else
// /usr/bin/python3 (Debian's, where python3-matplotlib installs, when PATH finds another).
// Throws planet::Error with one line naming what is missing.
std::string findPlotPython();

// Writes the plot of `csv` (FrameBenchReport::csv) to `pngPath`, atomically. Throws
// planet::Error with one line on failure.
void writeFramePlot(const std::string& python, const std::string& csv, const std::string& pngPath,
                    const std::string& title);

}  // namespace planet::cli
