#include "analytic/bounce_percentiles.h"
