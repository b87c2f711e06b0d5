"""Unit tests of the generator: ``python3 -m unittest discover -s ucon/tests -t .``."""
