#pragma once
/// Rasterising a mesh's UV layout into texels, and gutter dilation past UV seams.
