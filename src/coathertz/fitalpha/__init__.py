"""The offline fit of the refitted alpha rule (``coathertz fit-alpha``): training and validation
sweeps through the result store (:mod:`~coathertz.fitalpha.sweep`), the least-squares fits
(:mod:`~coathertz.fitalpha.fit`, :mod:`~coathertz.fitalpha.corrected`) and the build of the
shipped data file (:mod:`~coathertz.fitalpha.build`). The shipped rule
(:mod:`coathertz.closedform.refit`) reads that file without importing any of this.
"""
