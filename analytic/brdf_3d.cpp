#include "analytic/brdf_3d.h"
