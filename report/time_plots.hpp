#pragma once
// Time-history figures of a run (docs/plots.md): the quantity over the whole record, the sliding
// speed in its own panel beneath (never drawn over the torque), and, when the run oscillates
// (the shudder detector's verdict on the recording, report/plot_data.hpp), two detail panels
// of a few periods each: around the onset and at the end of the oscillating part, where the
// waveform and its phase against the slip can be read (none when those periods would take more
// than a third of the record: the whole-record panel shows them already). The whole-record panels draw a record
// denser than the image as its envelope (the minimum and maximum of each pixel-wide slice, in
// time order), which keeps its outline and avoids the moiré a line through thousands of periods
// makes.
//
//   torque       torque_Nm and (dashed) clutch_torque_Nm; slip_rpm (or speed_rpm) below; a
//                network run: every clutch's CLUTCH.torque_Nm, their CLUTCH.slip_rpm below
//   coupling     a driveline's coupling_torque_Nm and (dashed) rear_axle_torque_Nm;
//                coupling_slip_rpm below
//   temperature  temp_C, ir_temp_C, sump_temp_C, interface_max_temp_C (and a network's
//                CLUTCH.interface_max_temp_C), each with its own colour, dash and marker
//
// io::InputError naming `source` when the recording lacks what the figure needs.

#include <string>
#include <vector>

#include "dynamics/recording.hpp"
#include "report/gnuplot.hpp"

namespace shudder::report {

MultiPlot torque_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);
MultiPlot coupling_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);
MultiPlot temperature_plot(const dynamics::Recording& rec, const std::string& name, const std::string& source);

/// `s` thinned for an image about `bins` pixels wide: unchanged when it has at most 4 points per
/// bin; else per bin of consecutive points its smallest and largest value, in the order they
/// occur (a bin without finite points becomes a gap).
Series envelope(const Series& s, std::size_t bins);

/// The points of `s` with from_x <= x <= to_x.
Series slice(const Series& s, double from_x, double to_x);

}  // namespace shudder::report
