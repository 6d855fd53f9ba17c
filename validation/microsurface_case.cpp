#include "validation/microsurface_case.h"
