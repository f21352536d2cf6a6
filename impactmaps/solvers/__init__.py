"""Impact solvers: modal, compact (half-space) and closed-form asymptotes."""
