#pragma once
/// The POV-Ray bridge: a nenrin scene written as a twin POV-Ray 3.7 scene
/// (docs/povray-bridge.md says what maps exactly and what is approximated).
///  - camera: exact pinhole match (POV's horizontal `angle` from the vertical FOV, `right -x`
///    keeps the right-handed, Y-up scene as it is);
///  - distant lights: parallel lights of colour E / pi, so `finish { ambient 0 diffuse 1 }`
///    gives albedo E cos / pi like a Lambert surface; point lights: POV lights do not fall off,
///    so a fade of power 2 from a tiny distance d gives I / D^2 to a relative (d / D)^2;
///  - boxes and meshes (mesh2), with their rigid transforms as `matrix`;
///  - diffuse materials exactly; glossy and metal approximately; wood as its albedo baked into
///    16-bit df3 volumes (R, G, B) over the object's bounds, sampled in object space so
///    laminated products keep every board.
/// Rect lights and the environment's lighting are not exported (POV-Ray would need area
/// lights and radiosity); a constant environment becomes the background colour.

#include <string>
#include <vector>

#include "renderer/scene.h"

namespace nenrin {

struct PovExportOptions {
    int volumeResolution = 128;  ///< df3 samples along the longest side of a wood object
    int threads = 0;
    bool quiet = false;
};

/// What the export writes: its df3 volumes dominate (a `--volume 1024` twin is gigabytes).
struct PovOutputSize {
    double bytes = 0;  ///< of the df3 files
    int volumes = 0;   ///< wood objects, each with its R, G, B and knot files
};
PovOutputSize povOutputSize(const Scene& scene, const PovExportOptions& options);

/// Writes FOLDER/scene.pov, FOLDER/scene.ini (resolution and the reference render options) and
/// the df3 volumes of the wood objects. Returns the files written. Refuses up front (InputError)
/// when the volumes would not fit the disk's free space or the memory limit (requireOutputSpace).
std::vector<std::string> exportPovScene(const Scene& scene, const std::string& folder,
                                        const PovExportOptions& options);

}  // namespace nenrin
