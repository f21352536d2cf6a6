"""The exact-step integrator of the modal solver and its compiled stages (numba)."""
