#pragma once
/// Lat-long environment maps (OpenImageIO) with importance sampling.
