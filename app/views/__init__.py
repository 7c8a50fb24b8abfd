"""Plot views: each displays result objects pulled by its tab, and does nothing else."""
