"""Exact axisymmetric frictionless contact of a paraboloid on layered bodies (the ``axisym`` method).

Placeholder docstring; see the full version below.
"""

from coathertz.axisym.method import AxisymMethod

__all__ = ["AxisymMethod"]
