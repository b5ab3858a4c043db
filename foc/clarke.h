/* clarke.h - Clarke transform: two measured phase currents to alpha/beta. */
#ifndef CLARKE_H
#define CLARKE_H

#include "frames.h"

/*
 * clarke_forward(ia, ib): amplitude-invariant Clarke with ic = -ia - ib.
 *   alpha = ia
 *   beta  = (ia + 2 ib) / sqrt(3)
 *   Inputs and outputs Q15 of the same full scale. ia + 2 ib is formed in
 *   32 bits, multiplied by Q15(1/sqrt(3)), rounded to nearest and saturated
 *   (beta can exceed full scale only when |ia + 2 ib| > sqrt(3), i.e. for
 *   inputs that are not a balanced three-phase set).
 */
ab_q15_t clarke_forward(q15_t ia, q15_t ib);

#endif /* CLARKE_H */
