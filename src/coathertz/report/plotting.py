"""Former home of the plot helpers, now :mod:`coathertz.figstyle`; re-exported for old imports."""

from coathertz.figstyle import colour, figure, method_handles, method_style, save, series

__all__ = ["colour", "figure", "method_handles", "method_style", "save", "series"]
