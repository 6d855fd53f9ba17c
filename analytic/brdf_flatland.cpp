#include "analytic/brdf_flatland.h"
