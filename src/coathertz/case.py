"""The contact case shared by every method: two bodies, a load, their orientation.

Normalisation follows the paper (Section 1.3 and docs/paper-notes.md):

* elastic substrate(s): ``a0s, p0s, delta0s`` are the Hertz values with the coatings
  removed, ``H = h / a0s`` (eq 7a), bars are ratios to the ``s`` values;
* a coated body on a rigid substrate: ``a0c, p0c, delta0c`` are the Hertz values with the
  coating taken as a half-space, ``H = h / a0c`` (eq 7b), bars are ratios to the ``c`` values.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from coathertz.closedform.hertz import (
    HertzElliptical,
    combined_modulus,
    hertz_elliptical,
    relative_radii,
)
from coathertz.errors import CoatHertzError, check_positive
from coathertz.materials import INTERFACES, Body, Coating, Material


@dataclass(frozen=True)
class Normalisers:
    """Reference Hertz values used to non-dimensionalise a case (eq 7)."""

    kind: str  # "s" (coating removed) or "c" (coating as half-space)
    a0: float
    p0: float
    delta0: float
    r_a0: float
    r_b0: float


@dataclass(frozen=True)
class ContactCase:
    """Two bodies pressed together by a normal load.

    Parameters
    ----------
    body1, body2
        The contacting bodies. By convention body1 is the indenter (often a rigid sphere)
        and body2 the coated half-space, but nothing depends on the order.
    W
        Normal load [N], ``0 < W < inf``.
    theta
        Angle [rad] between the principal axes of the two bodies, eq (3b).
    label
        Optional name used in reports and the result store.
    """

    body1: Body
    body2: Body
    W: float
    theta: float = 0.0
    label: str = ""

    @property
    def is_stacked(self) -> bool:
        """A body carries a layer stack: only stack-aware methods (axisym, fft) solve it."""
        return self.body1.is_stacked or self.body2.is_stacked

    def __post_init__(self) -> None:
        for name in ("body1", "body2"):
            if not isinstance(getattr(self, name), Body):
                raise CoatHertzError(f"{name} must be a Body, got {getattr(self, name)!r}")
        check_positive("W", self.W)
        object.__setattr__(self, "W", float(self.W))
        if not math.isfinite(float(self.theta)):
            raise CoatHertzError(f"theta must be a finite angle in radians, got {self.theta!r}")
        object.__setattr__(self, "theta", float(self.theta))
        if self.body1.is_rigid and self.body2.is_rigid:
            raise CoatHertzError("at least one body must be elastic (both are rigid)")
        self.radii  # validates the geometry  # noqa: B018

    # -- constructors ----------------------------------------------------------------
    @classmethod
    def sphere_on_coated_half_space(
        cls,
        R: float,
        W: float,
        coating: Material,
        h: float,
        substrate: Material,
        indenter: Material | None = None,
        label: str = "",
    ) -> ContactCase:
        """The paper's configuration: a sphere of radius ``R`` (rigid unless ``indenter``)
        on a half-space of ``substrate`` coated with ``coating`` of thickness ``h``."""
        body1 = Body.rigid_sphere(R) if indenter is None else Body.sphere(indenter, R)
        body2 = Body.half_space(substrate, Coating(coating, h))
        return cls(body1, body2, W, label=label)

    def replace(self, **changes) -> ContactCase:
        """A copy with fields changed (``dataclasses.replace``)."""
        from dataclasses import replace

        return replace(self, **changes)

    def with_thickness(self, h: float) -> ContactCase:
        """The same case with every coating's thickness set to ``h``."""
        bodies = []
        for b in (self.body1, self.body2):
            if b.coating is not None:
                b = Body(b.material, Coating(b.coating.material, h, b.coating.interface), b.Rx, b.Ry, b.name)
            bodies.append(b)
        return self.replace(body1=bodies[0], body2=bodies[1])

    # -- geometry --------------------------------------------------------------------
    @cached_property
    def radii(self) -> tuple[float, float]:
        """Principal relative radii ``(Rx, Ry)``, ``Rx >= Ry``, eq (3)."""
        b1, b2 = self.body1, self.body2
        return relative_radii(b1.Rx, b1.Ry, b2.Rx, b2.Ry, self.theta)

    @property
    def Rx(self) -> float:
        return self.radii[0]

    @property
    def Ry(self) -> float:
        return self.radii[1]

    @property
    def R(self) -> float:
        """Equivalent radius sqrt(Rx Ry) (Section 1.2); 1/R = 1/R1 + 1/R2 for spheres."""
        return math.sqrt(self.Rx * self.Ry)

    @property
    def is_circular(self) -> bool:
        return math.isclose(self.Rx, self.Ry, rel_tol=1e-12)

    # -- materials -------------------------------------------------------------------
    @cached_property
    def coated_bodies(self) -> tuple[Body, ...]:
        return tuple(b for b in (self.body1, self.body2) if b.is_coated)

    @property
    def is_coated(self) -> bool:
        return bool(self.coated_bodies)

    def interface_for(self, setting: str = "bonded") -> str:
        """The coating/substrate interface a method models for this case.

        ``frictionless`` when a coated body's coating says so
        (:attr:`~coathertz.materials.Coating.interface`) or the method's own ``setting`` asks for
        it (a study's variant solving bonded cases as frictionless); else ``bonded``. A
        frictionless coating in the case is therefore never solved as a bonded one, whatever the
        method's default.
        """
        if setting not in INTERFACES:
            raise CoatHertzError(f"interface must be one of {list(INTERFACES)}, got {setting!r}")
        if setting == "frictionless" or any(b.coating.interface == "frictionless"
                                            for b in self.coated_bodies):
            return "frictionless"
        return "bonded"

    @property
    def E_star_s(self) -> float:
        """E* of eq (2) with the coatings removed (substrates only)."""
        return combined_modulus(self.body1.compliance_substrate, self.body2.compliance_substrate)

    @property
    def E_star_c(self) -> float:
        """E* of eq (2) with each coating taken as a half-space."""
        return combined_modulus(self.body1.compliance_coating, self.body2.compliance_coating)

    @property
    def rigid_substrate(self) -> bool:
        """True if a coated body sits on a rigid substrate (eq 7b normalisation)."""
        return any(b.material.is_rigid for b in self.coated_bodies)

    # -- Hertz references ------------------------------------------------------------
    def hertz(self, E_star: float) -> HertzElliptical:
        """Hertz solution of this geometry and load with equivalent modulus ``E_star``."""
        return hertz_elliptical(self.W, self.Rx, self.Ry, E_star)

    @cached_property
    def hertz_s(self) -> HertzElliptical:
        """Hertz values with the coatings removed (a0s, p0s, delta0s)."""
        return self.hertz(self.E_star_s)

    @cached_property
    def hertz_c(self) -> HertzElliptical:
        """Hertz values with the coatings as half-spaces (a0c, p0c, delta0c)."""
        return self.hertz(self.E_star_c)

    @property
    def a0s(self) -> float:
        return float(self.hertz_s.a0)

    @property
    def p0s(self) -> float:
        return float(self.hertz_s.p0)

    @property
    def delta0s(self) -> float:
        return float(self.hertz_s.delta0)

    @property
    def a0c(self) -> float:
        return float(self.hertz_c.a0)

    @property
    def p0c(self) -> float:
        return float(self.hertz_c.p0)

    @property
    def delta0c(self) -> float:
        return float(self.hertz_c.delta0)

    @cached_property
    def normalisers(self) -> Normalisers:
        """The paper's normalisers: ``c`` values for a rigid substrate, else ``s`` (eq 7)."""
        h = self.hertz_c if self.rigid_substrate else self.hertz_s
        kind = "c" if self.rigid_substrate else "s"
        return Normalisers(kind, float(h.a0), float(h.p0), float(h.delta0), float(h.r_a0), float(h.r_b0))

    def H_of(self, body: Body) -> float:
        """Dimensionless thickness of ``body``'s coating, eq (7a) or (7b)."""
        if body.coating is None:
            raise CoatHertzError("H is undefined for an uncoated body")
        return body.coating.h / self.normalisers.a0

    @property
    def H(self) -> float:
        """Dimensionless coating thickness h/a0s (eq 7a) or h/a0c (eq 7b).

        Raises if the two bodies carry coatings of different thickness.
        """
        coated = [b for b in (self.body1, self.body2) if b.coating is not None]
        if not coated:
            raise CoatHertzError("H is undefined: neither body is coated")
        hs = {b.coating.h for b in coated}
        if len(hs) > 1:
            raise CoatHertzError("the two coatings differ in thickness: use H_of(body)")
        return self.H_of(coated[0])

    @property
    def modulus_ratio(self) -> float:
        """E = Ec*/Es* of the (single kind of) coating, eq (19)."""
        coated = [b for b in (self.body1, self.body2) if b.coating is not None]
        if not coated:
            raise CoatHertzError("E = Ec*/Es* is undefined: neither body is coated")
        ratios = {b.modulus_ratio for b in coated}
        if len(ratios) > 1:
            raise CoatHertzError("the two coated bodies have different E = Ec*/Es*")
        return coated[0].modulus_ratio

    def _radius_text(self) -> str:
        """The geometry as a reader needs it: one R for a circular contact, saying when it is
        the equivalent radius of two curved bodies (1/R = 1/R1 + 1/R2); relative radii else."""
        def mm(x: float) -> str:
            return "inf" if math.isinf(x) else f"{x * 1e3:.4g} mm"

        curved = [b for b in (self.body1, self.body2) if math.isfinite(b.Rx) or math.isfinite(b.Ry)]
        if self.is_circular:
            if len(curved) == 2 and all(b.Rx == b.Ry for b in curved):
                return (f"R={mm(self.R)} (equivalent radius, 1/R = 1/R1 + 1/R2; "
                        f"R1={mm(self.body1.Rx)}, R2={mm(self.body2.Rx)})")
            return f"R={mm(self.R)}"
        return f"Rx={mm(self.Rx)} Ry={mm(self.Ry)} (relative radii, eq 3)"

    def describe(self) -> str:
        """One-line human-readable summary (report labels)."""
        parts = [f"W={self.W:g} N", self._radius_text()]
        for i, b in enumerate((self.body1, self.body2), start=1):
            sub = "rigid" if b.material.is_rigid else f"E={b.material.E / 1e9:.4g} GPa nu={b.material.nu:g}"
            txt = f"body{i}: {sub}"
            if b.coating is not None:
                c = b.coating
                txt += f" + coating E={c.material.E / 1e9:.4g} GPa nu={c.material.nu:g} h={c.h * 1e6:.4g} um"
                if c.interface != "bonded":
                    txt += f" ({c.interface} interface)"
            for j, L in enumerate(b.layers, 1):
                txt += (f" + layer {j} E={L.material.E / 1e9:.4g} GPa nu={L.material.nu:g} "
                        f"h={L.h * 1e6:.4g} um")
                if L.interface == "frictionless":
                    txt += " (frictionless below)"
            parts.append(txt)
        return "; ".join(parts)

    # -- two identical bodies ------------------------------------------------------------
    #: The approach of the pair is this many times the approach of its equivalent problem.
    IDENTICAL_PAIR_DELTA_FACTOR = 2.0

    @property
    def is_identical_pair(self) -> bool:
        """Two identical elastic bodies in a circular contact (same substrate, coating and
        thickness, hence the same radius of each other's image)."""
        b1, b2 = self.body1, self.body2
        return (self.is_circular and not b1.is_rigid and b1.material == b2.material
                and b1.coating == b2.coating and b1.layers == b2.layers)

    def identical_pair_equivalent(self) -> ContactCase | None:
        """The exactly equivalent single-body problem of two identical bodies, or ``None``.

        Under the half-space assumption both bodies carry the same pressure and deform alike,
        so the pair is one of them, as a (coated) half-space, pressed by a rigid sphere of radius
        ``2 R`` (``R`` the equivalent radius of the pair) with the same load; the pair's approach
        is :attr:`IDENTICAL_PAIR_DELTA_FACTOR` (2) times the equivalent's, ``a`` and ``p0`` are
        the same.
        """
        if not self.is_identical_pair:
            return None
        from coathertz.materials import RIGID

        b1 = self.body1
        R2 = 2.0 * self.R
        return ContactCase(Body(RIGID, None, R2, R2, name="rigid sphere"),
                           Body(b1.material, b1.coating, layers=b1.layers),
                           self.W, label=f"{self.label} (equivalent)" if self.label else "")


def bars(case: ContactCase, res: Mapping[str, Any]) -> dict[str, float]:
    """The paper's bars of a result (``a``, ``p0``, ``delta``, ``r_a``, ``r_b`` in SI): ratios to
    the eq (7) normalisers of ``case`` (``a0s`` ... on an elastic substrate, ``a0c`` ... on a rigid
    one)."""
    n = case.normalisers
    return {
        "a_bar": res["a"] / n.a0,
        "p_bar": res["p0"] / n.p0,
        "delta_bar": res["delta"] / n.delta0,
        "r_a_bar": res["r_a"] / n.r_a0,
        "r_b_bar": res["r_b"] / n.r_b0,
    }


def refuse_stack(case: ContactCase, method: str) -> None:
    """Raise one clear line if ``case`` has a layer stack that ``method`` does not model."""
    for name in ("body1", "body2"):
        body = getattr(case, name)
        if body.is_stacked:
            raise CoatHertzError(
                f"{method}: {name} has a stack of {len(body.layers)} layers, which {method} does not "
                "model (one coating at most); use axisym, the exact method for layer stacks")
