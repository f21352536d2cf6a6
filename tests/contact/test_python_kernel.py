"""A law's kernel run as Python (:attr:`ContactLaw.python_kernel`, what Python callers use: the
validity check's bisection, the any-law asymptotes) gives the compiled kernel's bits."""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.closed_forms.halfspace import single_law_parameters

from .test_contact_registry import LAWS, indentation_scale, law_from_registry


@pytest.mark.parametrize("name", LAWS)
def test_the_python_kernel_is_the_compiled_kernel_bit_for_bit(name):
    """Loading, unloading from a history and no contact, 2000 random states a decade or four
    either side of the law's indentation scale: the same IEEE operations and libm calls, so the
    same doubles (an exact comparison: any difference would change a map or a lookup)."""
    law = law_from_registry(name)
    params = single_law_parameters(law)
    rng = np.random.default_rng(7)
    for _ in range(2000):
        alpha_max = indentation_scale(law) * 10 ** rng.uniform(-4, 2)
        alpha = alpha_max if rng.random() < 0.3 else alpha_max * rng.uniform(-0.1, 1.0)
        compiled = np.array(law.kernel(alpha, alpha_max, params), float)
        python = np.array(law.python_kernel(alpha, alpha_max, params), float)
        assert compiled.tobytes() == python.tobytes(), (alpha, alpha_max, compiled, python)
