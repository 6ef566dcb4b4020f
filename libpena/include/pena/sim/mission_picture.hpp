#pragma once
// The overview picture of a simulated mission (DIR/mission.png): true walls, the a priori plan
// in another colour, smoke and magnetic zones, every entity's true path, a few scans drawn at
// their true poses, a scale bar and a legend.

#include <opencv2/core.hpp>

#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::sim {

// Picture options.
struct MissionPictureOptions {
  viz::MapCanvasOptions canvas = DefaultCanvas();  // 5 cm/px, <= 2000 px, legend panel right
  int scans_per_entity = 6;  // scans drawn per entity, spread evenly over its mission

  static viz::MapCanvasOptions DefaultCanvas() {
    viz::MapCanvasOptions canvas;
    canvas.legend_panel_px = 230;
    return canvas;
  }
};

// Renders the mission as a BGR image; deterministic for a given result.
cv::Mat RenderMission(const Scenario& scenario, const SimulationResult& result,
                      const MissionPictureOptions& options = {});

}  // namespace pena::sim
