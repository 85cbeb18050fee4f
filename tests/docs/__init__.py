"""The committed pages made again from their tables (docs/)."""
