"""Beams: the Beam target (:mod:`.beam`), one module per method of its modes (closed-form SS
modes, classical Euler modes, p-version finite elements), its exact static compliance and
section types. Equations, methods and accuracy: docs/physics.rst (Beam targets)."""
