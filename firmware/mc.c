/* mc.c - placeholder while the core is written. */
#include "mc.h"
