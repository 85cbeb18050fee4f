"""The benchmark scripts start and refuse bad options (bench/)."""
