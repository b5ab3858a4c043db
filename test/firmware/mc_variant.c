/* mc_variant.c - the core's source again, for the test builds with other UserParms.h switches. */
/* (Compiled here rather than as firmware/mc.c so the variant flags stay with the tests.) */
#include "../../firmware/mc.c"
