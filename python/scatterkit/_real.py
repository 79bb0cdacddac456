"""Arguments as arrays of real numbers."""

import numpy as np


def real_array(x, name="argument"):
    """``x`` as a float64 array. ``TypeError`` for complex values: numpy
    would drop their imaginary parts with only a warning, and a complex
    cosine or uniform is a mistake, not a number to round."""
    a = np.asarray(x)
    if np.iscomplexobj(a):
        raise TypeError(f"{name}: expected real numbers, got complex ones")
    return np.asarray(a, dtype=np.float64)
