# Convenience targets (the README's two commands are the canonical ones).
.PHONY: test test-slow bench
test:
	python -m pytest -q
test-slow:
	python -m pytest -q -m slow
bench:
	python -m ssl_marl.bench
