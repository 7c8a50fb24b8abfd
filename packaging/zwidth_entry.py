"""Entry point of the frozen (PyInstaller) zwidth: the same as the ``zwidth`` console script.

``ZWIDTH_SELFTEST=1`` runs the hidden self-check (app/selftest.py) instead; tests/test_packaging.py
uses it to prove the build contains the profiles, the icon and pyqtgraph's data.
"""

import os
import sys

if __name__ == "__main__":
    # the process pool of analysis.sampled.batch (zwidth space --batch) starts workers by
    # re-running this executable: PyInstaller's documented hook for that
    import multiprocessing

    multiprocessing.freeze_support()
    if os.environ.get("ZWIDTH_SELFTEST") == "1":
        from app.selftest import run_selftest

        sys.exit(run_selftest())
    from app.cli import main

    sys.exit(main())
