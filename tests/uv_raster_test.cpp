#include "renderer/uv_raster.h"
