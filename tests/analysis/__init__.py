"""The analysis of a study's tables: fits, theories, statistics, pages (analysis/)."""
