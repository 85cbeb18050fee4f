"""Friction on the sliding branch across resolutions: the levels of
studies/sliding_branch*.toml, one seed's surface the same at every level
(``steps``: paired steps; ``limit``: the chain's covariance and limit)."""
