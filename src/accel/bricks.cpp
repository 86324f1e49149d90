#include "accel/bricks.h"
