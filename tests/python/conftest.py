"""Shared set-up of the Python module's tests: the examples folder on the import path."""
import os
import sys

sys.path.insert(0, os.environ.get("DEFORM_EXAMPLES", os.path.join(os.path.dirname(__file__), "../../examples/python")))
