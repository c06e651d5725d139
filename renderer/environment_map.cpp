#include "renderer/environment_map.h"
