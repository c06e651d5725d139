#include "renderer/obj_mesh.h"
