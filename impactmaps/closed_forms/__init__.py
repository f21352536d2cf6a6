"""Closed forms and local answers: the infinite plate and beam, the quasi-static and half-space impacts, the any-law asymptotes and the similarity numbers."""
