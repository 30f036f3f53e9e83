"""The closed form as a method: Hertz, the paper's extended Hertz theory and its alpha, the
literature formulas, the refitted rule, and the adapter that registers them as the method
``closed-form``.

Modules
-------
:mod:`~coathertz.closedform.hertz`
    Hertz's circular and elliptical contacts, eqs (1)-(6).
:mod:`~coathertz.closedform.extended`, :mod:`~coathertz.closedform.alpha`
    The extended theory, eqs (13)-(21), and the paper's alpha (Appendix A, eqs 19 and 21).
:mod:`~coathertz.closedform.literature`
    The earlier single-layer formulas the paper compares with (eqs 8-12).
:mod:`~coathertz.closedform.refit`
    The refitted rule as shipped: its coefficients (``coathertz/data/alpha_refit.json``) and their
    evaluation, nothing of the fit (that is :mod:`coathertz.fitalpha`, which this package never
    imports).
:mod:`~coathertz.closedform.method`
    ``ClosedFormMethod``, the registered method.

Importing this package loads none of them; import the module you need.
"""
