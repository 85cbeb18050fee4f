"""The notebook, run under a Jupyter kernel (notebooks/)."""
