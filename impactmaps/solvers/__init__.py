"""Impact solvers: modal (exact-step integrator), half-space, and closed-form asymptotes."""
