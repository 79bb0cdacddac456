// The generated header used from C++ (extern "C" guard, enum types), built
// with -Wall -Wextra -Werror and run.
#include <cstdio>

#include "scatterkit.h"

int main() {
    sk_phase p;
    if (sk_phase_new_hg(0.5f, &p) != SK_OK) return 1;
    const sk_rayleigh_method m = SK_RAYLEIGH_DIRECT;
    const float mu = sk_phase_sample_cos(&p, 0.5f);
    std::printf("C++: HG(0.5) median cos theta %.6f, method %u\n", mu, static_cast<unsigned>(m));
    return (mu > 0.0f && mu < 1.0f) ? 0 : 1;
}
