"""The test suite. A package, so that its helper modules import as
``tests.helpers`` and ``tests.contact_case``: for a test package, pytest's
default ("prepend") import mode puts the repository's root first on the
import path, and nothing else needs to."""
