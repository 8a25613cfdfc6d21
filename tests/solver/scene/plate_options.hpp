#pragma once
// The scene the scene-option tests start from: the paper's plate with a hole
// (docs/method.md section 7.1) as flat options, which each test changes.
#include <map>
#include <string>

namespace bapd::test {

using PlateOptions = std::map<std::string, std::string>; // name -> value ("" for none)

inline PlateOptions PlateWithHole()
{
  return {
    {"-body_width", "0.08"},
    {"-body_height", "0.16"},
    {"-body_thickness", "0.001"},
    {"-body_dx", "0.001"},
    {"-body_holes", "0.04,0.08,0.01"},
    {"-material_bulk_ratio", "100"},
    {"-load_sets", "top,bottom"},
    {"-load_top_region", "top"},
    {"-load_top_x", "fixed"},
    {"-load_top_y", "stretch"},
    {"-load_top_y_scale", "0.5"},
    {"-load_bottom_region", "bottom"},
    {"-load_bottom_x", "fixed"},
    {"-load_bottom_y", "stretch"},
    {"-load_bottom_y_scale", "-0.5"},
    {"-load_schedule", "0,1,1,1.5,2,1.5"},
    {"-probes", "left_mid"},
    {"-probe_left_mid_at", "0,0.08"},
    {"-damping", "20"},
    {"-output_dir", "out/plate"},
    {"-output_interval", "200"},
  };
}

} // namespace bapd::test
