#include "validation/scene.h"
