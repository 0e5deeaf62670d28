// Shadow acne and three's shadow maps (suite ThreeShadowBias, ctest three.bias): filled in below.
#include "ThreePage.h"
