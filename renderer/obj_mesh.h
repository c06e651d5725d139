#pragma once
/// Triangle meshes from Wavefront OBJ files (tinyobjloader).
