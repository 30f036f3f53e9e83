r"""Exact axisymmetric frictionless contact of a paraboloid on layered bodies (method ``axisym``).

A semi-analytical solution of the circular contact problem of the paper (rigid or elastic sphere,
each body homogeneous or coated, elastic or rigid substrate, bonded or frictionless interface,
any Poisson's ratio up to 0.5) under load control: ``W`` in; ``delta``, ``a``, the maximum
pressure ``p0`` and its radius ``meta["r_p0"]``, and the profiles ``p(r)``, ``u_z(r)`` out. The
contact radius is an unknown fixed by the smooth-edge condition, not estimated from a grid. It is
the arbiter of the suite's axisymmetric studies (``reference_rank = 30``).

Kernel (:mod:`coathertz.axisym.kernel`)
---------------------------------------
With the Hankel transform ``P(k) = int_0^a p(r) J0(kr) r dr`` the combined surface displacement
of the two bodies is ``u(r) = int_0^inf C(k) P(k) J0(kr) k dk`` with

.. math::  C(k) = \frac{2}{E_{ref}\,k}\,\bigl(1 + M(k)\bigr),\qquad
           M(k) = E_{ref} \sum_i \frac{1-\nu_i^2}{E_i}\bigl(F_i(k h_i) - 1\bigr),

``E_ref`` the ``E*`` of eq (2) with each coating taken as a half-space and ``F_i`` the layer
factor of body ``i`` (eq 13 for a bonded coating on an elastic substrate; closed forms derived in
:mod:`~coathertz.axisym.kernel` for a rigid substrate and for a frictionless interface). ``M`` is
bounded (``M(0) = E_ref/E_s - 1``; ``-1`` on a rigid base) and decays like
``(kh)^2 exp(-2kh)``. The homogeneous part ``2/(E_ref k)`` is treated exactly (Sneddon/Abel);
only ``M`` enters a numerical integral. Two identical coated bodies simply give two equal terms.

*Layer stacks* (``Body.layers``, top first, each interface bonded or frictionless, elastic
or rigid substrate): ``F_i`` is the N-layer factor of :mod:`coathertz.stack` (bounded
exponentials only, a 4x6 null space per ``k``; equal to the closed forms above for N = 1 to 1e-14),
tabulated once per body on Chebyshev panels in ``log kh`` (checked against direct evaluation to
1e-13, else evaluated directly); ``h`` in ``M`` and the mode rule is the thinnest layer.

Formulation (Abel route, Fredholm equation of the second kind)
--------------------------------------------------------------
Writing ``P(k) = int_0^a theta(t) cos(kt) dt`` with
``theta(t) = (2/pi) int_t^a r p(r) / sqrt(r^2 - t^2) dr = (E_ref/pi) g(t)`` and applying the
Abel operator ``d/dt int_0^t r u(r)/sqrt(t^2 - r^2) dr`` to the contact condition
``u = delta - r^2/(2R)`` (``int_0^inf cos kt cos ks dk = (pi/2) delta(t - s)``) gives, with
``x = t/a``, ``xi = k a``,

.. math::  g(x) + \frac{2}{\pi}\int_0^1 \tilde K(x,y)\,g(y)\,dy = \delta - \frac{a^2}{R}x^2,\qquad
           \tilde K(x,y) = \int_0^\infty M(\xi/a)\cos\xi x\,\cos\xi y\,d\xi .

Then ``W = 2 E_ref a int_0^1 g dx``, the smooth edge (finite pressure at ``r = a``) is
``g(1) = 0``, and the pressure is the Abel inversion
``p(rho a) = -(E_ref/(pi a)) int_rho^1 g'(x)/sqrt(x^2 - rho^2) dx``. For ``M = 0``:
``g = delta - a^2 x^2/R``, ``delta = a^2/R``, ``W = 4 E a^3/(3R)``, ``p = (2Ea/(pi R)) sqrt(1-rho^2)``:
eq (1), exactly.

Discretisation (:mod:`coathertz.axisym.solver`)
-----------------------------------------------
*Galerkin in even Legendre polynomials* (not Nystrom: for thin layers ``K~`` is a peak of width
``h/a`` around ``x = y``, which a Nystrom rule would have to resolve with ``N ~ a/h`` nodes):
``g = sum_n c_n P_{2n}(x)``; since ``int_0^1 P_{2m}(x) cos(xi x) dx = (-1)^m j_{2m}(xi)``, the
Galerkin matrix is ``diag(1/(4m+1)) + (2/pi) A`` with the one-dimensional integrals
``A_mn = int_0^inf M(xi/a) j_{2m}(xi) j_{2n}(xi) dxi``. The right-hand sides ``1`` and ``x^2``
have two non-zero moments; ``delta`` follows from ``g(1) = 0`` (linear in ``delta``) and ``W``
from ``c_0``. The thin-coating boundary layer of width ``h`` at the contact edge sets the number
of modes: ``N = 9 / sqrt(h/a)`` (rounded up to a multiple of 8, ``32 <= N <= 96``; thinner
layers: edge functions, below).

*The oscillating, slowly decaying xi integral*: the homogeneous (non-decaying) part of the
kernel never enters it; what remains, ``M(xi/a) j_{2m} j_{2n}``, decays like
``(xi h/a)^2 exp(-2 xi h/a) / xi^2`` and oscillates as ``cos 2 xi``. It is integrated on
``[0, 14 a/h]`` (``M ~ 1e-10`` there; the neglected tail changes the results by < 1e-10) by
composite Gauss--Legendre: geometric panels ``2^-14 .. 4`` (they resolve ``M`` for thick layers,
where it varies on the scale ``a/h``) then panels of width 4 with 8 nodes (2 nodes per unit of
``xi``; the oscillation has period ``pi``). Quadrature error at these defaults: < 1e-10 in
``delta``, ``a``, ``p0`` against 16 nodes per panel and a cut-off at ``30 a/h`` (six cases from
``H = 0.01`` to 3, rigid base ``nu_c = 0.5`` included). ``j_{2n}`` on the nodes come from one
three-term recurrence for all orders (upward for ``xi >= n``, Miller downward below), cached per
(modes, rule) and shared by all cases; each radius costs one ``J diag(w M) J^T`` product and an
``N x N`` LU solve.

*Thin layers, the xi tail* (``14 a/h > X0 = max(l^2/16, 512)``, ``l = 2N - 2``): the direct rule
stops at ``X0``; beyond, ``j_{2m} j_{2n}`` is written with the exact finite expansion of the
spherical Bessel functions (DLMF 10.49.2) as a smooth part plus ``Re(... e^{2i xi})``: the smooth
part is integrated on geometric Gauss panels (ratio 1.5, 16 nodes) to where ``M`` has decayed, the
oscillating part by parts at ``X0`` (four terms, derivatives by a 5-point stencil). Both agree with
the direct rule to 1e-11 in ``A`` (``tests/axisym/test_thin_layer.py``), and the quadrature's cost
and memory no longer depend on ``h``. The rule's own error on the constant part ``M(0)`` of the
weight (~1e-9 at 8 nodes per panel) is removed with the exact ``int_0^inf j_{2m} j_{2n} dxi =
pi/(2(4m+1)) delta_mn`` (Parseval; it mattered on a rigid base, where ``1 + M(0) = 0`` amplified it
to 3e-7 in delta for a thin incompressible layer). The layer term of ``u_z`` outside the contact is
integrated to ``X0`` (~1e-8 of ``delta``; noted in ``meta["u_z"]``).

*Thin layers, the edge boundary layer* (:mod:`coathertz.axisym.edge`): ``g`` has a boundary layer
of width ~``h`` at ``x = 1`` that Legendre modes resolve only with ``N^2 h/a ~ 4-12`` (a within 1e-8;
~600 modes at ``h/a = 1e-5``). Where the rule above would need more than 96 modes
(``h/a < 0.0088``), the basis is 64 Legendre modes plus edge functions ``exp((x - 1)/L_j)``, ``L_j``
geometric (ratio 1.25) from ``h/(32 a)`` to 1/64 (20-50 functions): their cosine transforms
``Re((e^{i xi} - e^{-1/L})/(1/L + i xi))`` are closed forms, so every Galerkin entry is the same
one-dimensional ``xi`` integral, with the same tail treatment (every basis function is
``Re(U e^{i xi})`` beyond ``X0``); the nearly dependent edge functions are handled in an orthonormal
basis of their span (Gram eigenvectors above 1e-15 of the largest). The smooth edge is then imposed
as stationarity of the load at fixed ``delta`` (``dW/da = 0`` with
``W = 2 E_ref a (delta P_1 - q P_12)`` from Galerkin energies and their exact ``a``-derivatives,
:func:`~coathertz.axisym.solver.solve_at_radius`), which is variational: ``g(1) = 0`` is a point
value at the boundary layer and converges slowly (48 modes, ``h/a = 1e-3``: 4e-6 against 1e-8).
The pressure imposes ``g(1) = 0`` in its Abel formula. Below
``h/a = 2e-8`` the layer moves delta, a, p0 by < 1e-8 and 32 Legendre modes with the energy condition
are used (a off by ~0.17 h/a). Measured (``tests/axisym/test_thin_layers.py``,
``tests/benchmarks/bench_axisym_thin.py``): against 400 Legendre modes at ``h/a = 1e-3``
(moduli 1/10-10, bonded and frictionless, ``nu_c = 0.49``, rigid bases with ``nu_c`` 0.3 and 0.5,
a two-layer stack) delta and a within 2e-10, p0 within 8e-9. Self-convergence
(``tests/axisym/test_thin_self_convergence.py``): edge bases with the same scale range and ratios
``1.25^(2^(3-k))`` (5.96 ... 1.057) are nested; on 17 seeded thin coatings and 2-4-layer stacks
(every layer at ``h/a`` 1e-5 to 1e-3) ``a`` converges geometrically to ~1e-13 and ``p0`` (about a
decade per level) to a floor of a few 1e-9, where the ~85 numerically independent directions of the
span saturate (``p0`` moves by ~1e-2 sqrt(GRAM_TOL) with the truncation); the default (ratio 1.25)
is within 2.2e-13 (delta), 8.9e-13 (a) and 8.1e-9 (p0) of every finer level and of 12 nodes per
panel. 16-24 ms CPU and 10-14 MiB traced peak per single coating from ``h/a = 1e-5`` to 0.003, the
1 nm B4C coating included (one core of a shared machine).

*Load control*: secant iteration on ``log W(a) - log W`` in ``log a`` (bracketed), started from
the Hertz radius with the compliance taken at ``k = 1.2/a`` and the slope of that model
(4-6 solves to ``|log W error| < 1e-12``).

*Pressure and peak*: ``p(rho)/sqrt(1 - rho^2)`` is a polynomial of degree ``N - 2`` in
``rho^2``; it is computed exactly (Gauss rule after ``x^2 = rho^2 + (1-rho^2)s^2``) at ``N + 1``
Chebyshev points and interpolated. The maximum (off the axis, on a ring, for stiff coatings, e.g.
``r = 0.70 a`` for ``E = 10``, ``H = 0.3``) is bracketed by a 129-point scan, zoomed and located by
a parabola. ``u_z`` outside the contact is Sneddon's
``(2/pi) int_0^1 g(x)/sqrt(rho^2 - x^2) dx`` plus the layer term on the same xi nodes.

Convergence evidence (relative differences to a reference with 160 modes, 20 nodes per panel,
cut-off 30 a/h; ``tests/axisym/test_convergence.py``)
--------------------------------------------------------------------------------------------
========================  ====  =====================================  ======================
case                      N     a at N = 8, 16, 24, 32, 48, 64          default (all of d, a, p0)
========================  ====  =====================================  ======================
E = 1/4, H = 0.01         80    1e-3, 3e-5, 1e-5, 1e-6, 2e-8, 9e-11     4e-12
E = 4, H = 0.01           64    2e-3, 2e-4, 3e-5, 2e-6, 2e-8, 2e-10     4e-10
E = 4, H = 0.3            16    8e-7, 3e-13 (round-off from N = 16)     6e-12
rigid base, nu_c = 0.5,   40    2e-5, 2e-8, 5e-12, ...                  2e-12
H = 0.05
========================  ====  =====================================  ======================

``delta`` converges fastest (6e-8 at N = 8 for H = 0.01), ``a`` and ``p0`` (edge quantities)
slowest; all converge geometrically in N. In the xi rule (panels of width 3) the error falls from
~1e-5 at 4 nodes per panel to ~1e-11 at 7-8 (about 1.5 decades per node).

Limits (``test_limits.py``): homogeneous bodies and a coating equal to its substrate reproduce eq
(1) to 1e-12 and 1e-10; ``h = 0`` is the substrate Hertz solution exactly; ``H -> inf`` extrapolates
(Richardson in 1/H) to the coating's Hertz values to 1e-8; ``H -> 0`` approaches the substrate's at
first order in H (``delta``, ``p0``; ``a`` at observed order ~0.8); thin layers on a rigid base
approach the Winkler layer (bonded: constrained modulus; frictionless: ``E_c*``) and, for ``nu_c =
0.5``, Matthewson's incompressible layer (eq 10) at first order in ``h/a``. FFT (n = 256) and FE
cross-checks are in ``test_crosscheck.py``; timings in ``tests/benchmarks/bench_axisym.py``.
"""

from coathertz.axisym.method import AxisymMethod

__all__ = ["AxisymMethod"]
