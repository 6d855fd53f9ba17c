#include "sim/microsurface3d.h"
