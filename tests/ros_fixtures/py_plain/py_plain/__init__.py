"""A plain Python package: no package.xml, its metadata in setup.cfg."""
