#include "renderer/colour_management.h"
