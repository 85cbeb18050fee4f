"""The C++ styles of potentials/ against independent implementations."""
