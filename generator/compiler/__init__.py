"""The compiler: the canonical model, the tables every target shares, the portable image, the one
naming rule, template rendering and the files the package ships; ``pipeline`` chains them."""
