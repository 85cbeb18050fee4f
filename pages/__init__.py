"""The pages: one class per page kind (pages.kinds) that takes a study's
numbers from analysis/, draws its figures and writes its Markdown."""
