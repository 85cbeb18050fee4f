"""The builder's lattices, scenes and data files (builder/)."""
