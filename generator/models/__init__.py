"""Working with models before and beside the compiler: synthesis through libFAUDES, the product
of local supervisors, equivalence, design properties, export and pictures."""
