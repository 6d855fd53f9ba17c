#include "validation/simulate.h"
