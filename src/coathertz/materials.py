"""Materials, coatings and bodies: the inputs shared by every method.

Nomenclature
------------
E, nu
    Young's modulus [Pa] and Poisson's ratio of an isotropic material.
E_star
    Plane-strain modulus E/(1 - nu^2) ("equivalent modulus" of the paper, below eq 2).
h
    Coating thickness [m].
mu, lam, kappa
    Shear-modulus ratio and the Dundurs-like constants of eq (13).

A rigid material has ``E = inf``; its ``E_star`` is infinite and its compliance zero,
so eqs (2) and (18) need no special case.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

from coathertz.errors import CoatHertzError, check_positive

#: The hardening laws a :class:`Plasticity` may name.
HARDENING_LAWS = ("perfect", "linear", "power", "table")


@dataclass(frozen=True)
class Plasticity:
    """J2 (von Mises) yield with isotropic hardening: the flow stress ``Y(ep)``.

    ``ep`` is the equivalent (accumulated) plastic strain, ``sqrt(2/3 eps_p : eps_p)`` summed
    over increments. Hardening laws:

    * ``perfect``: ``Y(ep) = Y``;
    * ``linear``: ``Y(ep) = Y + H ep``;
    * ``power`` (Swift): ``Y(ep) = Y (1 + ep / eps0)^n``;
    * ``table``: piecewise linear through ``table = ((0, Y), (ep_1, Y_1), ...)`` (``ep``
      increasing, first point ``(0, Y)``), constant after the last point.

    Parameters
    ----------
    Y
        Initial yield stress in uniaxial tension [Pa], ``0 < Y < inf``.
    hardening
        One of :data:`HARDENING_LAWS`.
    H
        Linear hardening modulus ``dY/dep`` [Pa], ``H >= 0`` (``linear`` only).
    n, eps0
        Power-law exponent ``0 <= n < 1`` and reference strain ``eps0 > 0`` (``power`` only).
    table
        ``(ep, Y)`` pairs [-, Pa] (``table`` only).
    """

    Y: float
    hardening: str = "perfect"
    H: float = 0.0
    n: float = 0.0
    eps0: float = 0.0
    table: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        check_positive("yield stress Y", self.Y)
        object.__setattr__(self, "Y", float(self.Y))
        if self.hardening not in HARDENING_LAWS:
            raise CoatHertzError(f"hardening must be one of {HARDENING_LAWS}, got {self.hardening!r}")
        if self.hardening == "linear" and not (0.0 <= float(self.H) < math.inf):
            raise CoatHertzError(f"linear hardening modulus H must satisfy 0 <= H < inf [Pa], "
                                 f"got {self.H!r}")
        if self.hardening == "power":
            if not (0.0 <= float(self.n) < 1.0):
                raise CoatHertzError(f"power-law hardening exponent n must satisfy 0 <= n < 1, "
                                     f"got {self.n!r}")
            check_positive("power-law reference strain eps0", self.eps0)
        if self.hardening == "table":
            try:
                tab = tuple((float(e), float(y)) for e, y in self.table)
            except (TypeError, ValueError) as exc:
                raise CoatHertzError(f"hardening table must be (ep, Y) pairs, got {self.table!r}") from exc
            ep = [t[0] for t in tab]
            if len(tab) < 2 or ep[0] != 0.0 or any(b <= a for a, b in itertools.pairwise(ep)):
                raise CoatHertzError("hardening table needs >= 2 (ep, Y) pairs, ep increasing from 0, "
                                     f"got {self.table!r}")
            if tab[0][1] != self.Y or any(y <= 0 for _, y in tab):
                raise CoatHertzError(f"hardening table must start at (0, Y = {self.Y:g}) with Y > 0, "
                                     f"got {self.table!r}")
            object.__setattr__(self, "table", tab)
        for k in ("H", "n", "eps0"):
            object.__setattr__(self, k, float(getattr(self, k)))

    def flow_stress(self, ep):
        """``(Y(ep), dY/dep)`` for an array of equivalent plastic strains ``ep >= 0``."""
        import numpy as np

        ep = np.asarray(ep, dtype=float)
        if self.hardening == "perfect":
            return np.full_like(ep, self.Y), np.zeros_like(ep)
        if self.hardening == "linear":
            return self.Y + self.H * ep, np.full_like(ep, self.H)
        if self.hardening == "power":
            x = 1.0 + ep / self.eps0
            return self.Y * x**self.n, self.Y * self.n / self.eps0 * x ** (self.n - 1.0)
        e = np.array([t[0] for t in self.table])
        y = np.array([t[1] for t in self.table])
        slope = np.append(np.diff(y) / np.diff(e), 0.0)
        i = np.clip(np.searchsorted(e, ep, side="right") - 1, 0, len(e) - 1)
        return y[i] + slope[i] * (np.minimum(ep, e[-1]) - e[i]), slope[i]

    def key(self) -> dict:
        """Canonical description (result-store key)."""
        d: dict = {"Y": self.Y, "hardening": self.hardening}
        if self.hardening == "linear":
            d["H"] = self.H
        elif self.hardening == "power":
            d.update(n=self.n, eps0=self.eps0)
        elif self.hardening == "table":
            d["table"] = [list(t) for t in self.table]
        return d


@dataclass(frozen=True)
class Material:
    """Isotropic linear-elastic material, optionally with J2 plasticity.

    Parameters
    ----------
    E
        Young's modulus [Pa], ``0 < E <= inf`` (``inf``: rigid).
    nu
        Poisson's ratio, ``-1 < nu <= 0.5``.
    name
        Optional label used in reports.
    plasticity
        Optional :class:`Plasticity` (yield stress and hardening); ``None``: elastic throughout.
        Only the FE model's incremental elastic-plastic solver uses it.
    """

    E: float
    nu: float
    name: str = field(default="", compare=False)
    plasticity: Plasticity | None = None

    def __post_init__(self) -> None:
        check_positive("Young's modulus E", self.E, allow_inf=True)
        if self.plasticity is not None:
            if not isinstance(self.plasticity, Plasticity):
                raise CoatHertzError(f"plasticity must be a Plasticity or None, got {self.plasticity!r}")
            if math.isinf(float(self.E)):
                raise CoatHertzError("a rigid material (E = inf) cannot have plasticity data")
        try:
            nu = float(self.nu)
        except (TypeError, ValueError) as exc:
            raise CoatHertzError(
                f"Poisson's ratio nu must be a number in (-1, 0.5], got {self.nu!r}") from exc
        if not (-1.0 < nu <= 0.5):
            raise CoatHertzError(f"Poisson's ratio nu must satisfy -1 < nu <= 0.5, got {self.nu!r}")
        object.__setattr__(self, "E", float(self.E))
        object.__setattr__(self, "nu", nu)

    @classmethod
    def rigid(cls) -> Material:
        """A rigid material (E = inf)."""
        return cls(math.inf, 0.0, name="rigid")

    @property
    def is_rigid(self) -> bool:
        return math.isinf(self.E)

    @property
    def E_star(self) -> float:
        """Plane-strain modulus E/(1 - nu^2) [Pa] (paper, below eq 2)."""
        if self.is_rigid:
            return math.inf
        return self.E / (1.0 - self.nu**2)

    @property
    def compliance(self) -> float:
        """(1 - nu^2)/E [1/Pa], the body's term in eq (2); zero for a rigid body."""
        return 0.0 if self.is_rigid else (1.0 - self.nu**2) / self.E

    @property
    def G(self) -> float:
        """Shear modulus E / (2 (1 + nu)) [Pa]."""
        return self.E / (2.0 * (1.0 + self.nu))


RIGID = Material.rigid()


#: Coating/substrate interfaces the case model knows: the paper's bonded layer and a layer
#: resting on its substrate without friction.
INTERFACES = ("bonded", "frictionless")


@dataclass(frozen=True)
class Coating:
    """A layer of uniform thickness ``h`` on its substrate.

    Parameters
    ----------
    material
        Coating material; must be elastic (a rigid coating is rejected).
    h
        Thickness [m], ``0 <= h < inf``.
    interface
        How the layer holds to its substrate (:data:`INTERFACES`): ``bonded`` (perfectly
        bonded, the paper's model, eq 13) or ``frictionless`` (resting on it without friction:
        normal displacement and normal stress continuous, no shear transmitted).
    """

    material: Material
    h: float
    interface: str = "bonded"

    def __post_init__(self) -> None:
        if self.interface not in INTERFACES:
            raise CoatHertzError(f"coating interface must be one of {list(INTERFACES)}, "
                                 f"got {self.interface!r}")
        if not isinstance(self.material, Material):
            raise CoatHertzError(f"coating material must be a Material, got {self.material!r}")
        if self.material.is_rigid:
            raise CoatHertzError("coating material must be elastic (0 < E < inf), got a rigid one")
        try:
            h = float(self.h)
        except (TypeError, ValueError) as exc:
            raise CoatHertzError(f"coating thickness h must be a number >= 0, got {self.h!r}") from exc
        if math.isnan(h) or h < 0 or math.isinf(h):
            raise CoatHertzError(f"coating thickness h must satisfy 0 <= h < inf [m], got {self.h!r}")
        object.__setattr__(self, "h", h)


#: How a layer's lower face is joined to what lies below it.
LAYER_INTERFACES = INTERFACES


@dataclass(frozen=True)
class Layer:
    """One layer of a stack: ``material``, thickness ``h`` [m], ``0 < h < inf``, and
    how its lower face is joined to what lies below (``bonded`` or ``frictionless``)."""

    material: Material
    h: float
    interface: str = "bonded"

    def check(self, where: str) -> None:
        """Raise one clear line naming ``where`` (e.g. ``body2 layer 2``) for bad data."""
        if not isinstance(self.material, Material):
            raise CoatHertzError(f"{where}: material must be a Material, got {self.material!r}")
        if self.material.is_rigid:
            raise CoatHertzError(f"{where}: material must be elastic (0 < E < inf), got a rigid one")
        try:
            h = float(self.h)
        except (TypeError, ValueError):
            raise CoatHertzError(f"{where}: thickness h must be a number > 0 [m], got {self.h!r}") from None
        if not (0.0 < h < math.inf):
            raise CoatHertzError(f"{where}: thickness h must satisfy 0 < h < inf [m], got {self.h!r}")
        if self.interface not in LAYER_INTERFACES:
            raise CoatHertzError(f"{where}: interface must be one of {LAYER_INTERFACES}, "
                                 f"got {self.interface!r}")


def graded_layers(E_of_z, nu_of_z, h: float, n: int, interface: str = "bonded") -> tuple[Layer, ...]:
    """A graded coating ``E(z), nu(z)`` (``0 <= z <= h`` from the surface down) as ``n`` equal
    layers, top first, each with the properties at its mid-depth (midpoint rule: the stack's
    ``delta``, ``a``, ``p0`` converge like ``1/n^2``; ``tests/multilayer/test_graded.py``).
    ``interface`` joins the last layer to the substrate; inside the grade all are bonded."""
    if not (isinstance(n, int) and n >= 1):
        raise CoatHertzError(f"graded coating: the layer count n must be an integer >= 1, got {n!r}")
    if not (0.0 < float(h) < math.inf):
        raise CoatHertzError(f"graded coating: thickness h must satisfy 0 < h < inf [m], got {h!r}")
    dz = float(h) / n
    out = []
    for i in range(n):
        z = (i + 0.5) * dz
        try:
            mat = Material(float(E_of_z(z)), float(nu_of_z(z)))
        except CoatHertzError as exc:
            raise CoatHertzError(f"graded coating layer {i + 1} (z = {z:.4g} m): {exc}") from None
        layer = Layer(mat, dz, interface if i == n - 1 else "bonded")
        layer.check(f"graded coating layer {i + 1}")
        out.append(layer)
    return tuple(out)


@dataclass(frozen=True)
class CoatingConstants:
    """Constants of the layered-body FRF, eq (13).

    ``mu = Ec (1 + nu_s) / (Es (1 + nu_c))`` (shear modulus ratio Gc/Gs),
    ``lam = 1 - 4 (1 - nu_c) / (1 + mu (3 - 4 nu_s))``,
    ``kappa = (mu - 1) / (mu + 3 - 4 nu_c)``.
    Rigid substrate: ``mu = 0``, ``lam = 4 nu_c - 3``, ``kappa = 1/lam`` (Section 4).
    """

    mu: float
    lam: float
    kappa: float


def lam_kappa(mu, nu_c, nu_s):
    """lambda and kappa of eq (13) from the shear-modulus ratio ``mu = Gc/Gs`` and the Poisson
    ratios (scalars or numpy arrays): the one place these constants are written down."""
    lam = 1.0 - 4.0 * (1.0 - nu_c) / (1.0 + mu * (3.0 - 4.0 * nu_s))  # eq (13)
    kappa = (mu - 1.0) / (mu + 3.0 - 4.0 * nu_c)  # eq (13)
    return lam, kappa


def lam_kappa_rigid(nu_c):
    """lambda and kappa on a rigid substrate (mu = 0, Section 4): ``lam = 4 nu_c - 3``, ``kappa = 1/lam``."""
    lam = 4.0 * nu_c - 3.0
    return lam, 1.0 / lam


def coating_constants(coating: Material, substrate: Material) -> CoatingConstants:
    """Return mu, lambda, kappa of eq (13) for ``coating`` on ``substrate``."""
    nu_c = coating.nu
    if substrate.is_rigid:
        lam, kappa = lam_kappa_rigid(nu_c)  # Section 4
        return CoatingConstants(0.0, lam, kappa)
    nu_s = substrate.nu
    mu = coating.E * (1.0 + nu_s) / (substrate.E * (1.0 + nu_c))  # eq (13)
    lam, kappa = lam_kappa(mu, nu_c, nu_s)
    return CoatingConstants(mu, lam, kappa)


@dataclass(frozen=True)
class Body:
    """One of the two contacting bodies.

    Parameters
    ----------
    material
        Substrate (bulk) material; ``RIGID`` for a rigid body or rigid substrate.
    coating
        Optional coating on the contacting surface.
    Rx, Ry
        Principal radii of curvature of the surface at the first point of contact [m];
        ``inf`` for a flat surface (half-space). Convex surfaces have positive radii.
    name
        Optional label.
    layers
        Optional stack of :class:`Layer` (top first) instead of ``coating``; only the
        methods that model stacks (``axisym``) accept a body with layers, the others refuse it.
    """

    material: Material
    coating: Coating | None = None
    Rx: float = math.inf
    Ry: float = math.inf
    name: str = field(default="", compare=False)
    layers: tuple[Layer, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.material, Material):
            raise CoatHertzError(f"body material must be a Material, got {self.material!r}")
        if self.coating is not None and not isinstance(self.coating, Coating):
            raise CoatHertzError(f"coating must be a Coating or None, got {self.coating!r}")
        if self.Rx == self.Ry:  # a sphere (or a flat surface): one radius, called R
            check_positive("radius R", self.Rx, allow_inf=True)
        else:
            check_positive("radius Rx", self.Rx, allow_inf=True)
            check_positive("radius Ry", self.Ry, allow_inf=True)
        object.__setattr__(self, "Rx", float(self.Rx))
        object.__setattr__(self, "Ry", float(self.Ry))
        object.__setattr__(self, "layers", tuple(self.layers))
        if self.layers:
            if self.coating is not None:
                raise CoatHertzError("a body takes either a coating or a layer stack, not both")
            for i, layer in enumerate(self.layers, 1):
                if not isinstance(layer, Layer):
                    raise CoatHertzError(f"layer {i} must be a Layer, got {layer!r}")
                layer.check(f"layer {i}")

    # constructors --------------------------------------------------------------
    @classmethod
    def rigid_sphere(cls, R: float) -> Body:
        """A rigid sphere of radius ``R`` [m] (the paper's indenter)."""
        return cls(RIGID, None, R, R, name="rigid sphere")

    @classmethod
    def sphere(cls, material: Material, R: float, coating: Coating | None = None) -> Body:
        return cls(material, coating, R, R)

    @classmethod
    def half_space(cls, material: Material, coating: Coating | None = None) -> Body:
        """A flat body (half-space), optionally coated."""
        return cls(material, coating)

    # derived -------------------------------------------------------------------
    @property
    def is_stacked(self) -> bool:
        """Carries a layer stack (``layers``), which only stack-aware methods model."""
        return bool(self.layers)

    @property
    def stack(self) -> tuple[Layer, ...]:
        """The layers, top first: ``layers``, or the single coating (with its interface), or ``()``."""
        if self.layers:
            return self.layers
        if not self.is_coated:
            return ()
        return (Layer(self.coating.material, self.coating.h, self.coating.interface),)

    @property
    def deformable_materials(self) -> tuple[Material, ...]:
        """The materials an FE model of this body meshes, top first: the coating (if any, of
        positive thickness), then the substrate unless it is rigid. The one place the FE, its
        plastic path and the CLI read which materials are in the model."""
        top = (self.coating.material,) if self.is_coated else ()
        return top + (() if self.material.is_rigid else (self.material,))

    @property
    def is_coated(self) -> bool:
        return self.coating is not None and self.coating.h > 0

    @property
    def is_rigid(self) -> bool:
        """Rigid throughout: rigid material and no (elastic) coating or layers."""
        return self.material.is_rigid and not self.is_coated and not self.layers

    @property
    def compliance_substrate(self) -> float:
        """(1 - nu^2)/E of the substrate alone (coating removed), eq (2)."""
        return self.material.compliance

    @property
    def compliance_coating(self) -> float:
        """(1 - nu^2)/E of the coating as a half-space: of a stack's top layer, of the substrate
        if uncoated."""
        if self.layers:
            return self.layers[0].material.compliance
        if self.coating is None:
            return self.material.compliance
        return self.coating.material.compliance

    @property
    def constants(self) -> CoatingConstants:
        """mu, lambda, kappa of eq (13) for this body's coating on its substrate."""
        if self.coating is None:
            raise CoatHertzError("body has no coating: coating constants are undefined")
        return coating_constants(self.coating.material, self.material)

    @property
    def modulus_ratio(self) -> float:
        """E = Ec*/Es* (eq 19); 0 for a rigid substrate."""
        if self.coating is None:
            raise CoatHertzError("body has no coating: modulus ratio E = Ec*/Es* is undefined")
        return self.coating.material.E_star / self.material.E_star
