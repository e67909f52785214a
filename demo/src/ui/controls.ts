// Small DOM builders for the control panel. Every control carries `data-control="<id>"`, the name
// the end-to-end tests and the features use to find it.
import { linearToSrgb, srgbToLinear } from '@plasius/gpu-renderer';

export interface Choice<T extends string> {
  value: T;
  label: string;
}

function element<K extends keyof HTMLElementTagNameMap>(tag: K, props: Partial<HTMLElementTagNameMap[K]> = {}, children: (Node | string)[] = []): HTMLElementTagNameMap[K] {
  const el = document.createElement(tag);
  Object.assign(el, props);
  for (const child of children) el.append(child);
  return el;
}

/** A titled group of controls in the panel. */
export function section(panel: HTMLElement, title: string, id: string): HTMLElement {
  const box = element('section', { className: 'panel-section' }, [element('h2', { textContent: title })]);
  box.dataset.section = id;
  panel.append(box);
  return box;
}

function row(parent: HTMLElement, id: string, label: string, control: HTMLElement): HTMLLabelElement {
  control.dataset.control = id;
  const wrapper = element('label', { className: 'control' }, [element('span', { textContent: label }), control]);
  parent.append(wrapper);
  return wrapper;
}

export function selectControl<T extends string>(parent: HTMLElement, id: string, label: string, choices: readonly Choice<T>[], value: T, onChange: (value: T) => void): HTMLSelectElement {
  const select = element('select', {}, choices.map((c) => element('option', { value: c.value, textContent: c.label })));
  select.value = value;
  select.addEventListener('change', () => onChange(select.value as T));
  row(parent, id, label, select);
  return select;
}

const rangeFormats = new WeakMap<HTMLInputElement, (v: number) => string>();

/**
 * A slider with its value printed beside it. `onInput` fires while dragging, or with
 * `commit: true` once on release (for settings that rebuild the renderer).
 */
export function rangeControl(
  parent: HTMLElement,
  id: string,
  label: string,
  options: { min: number; max: number; step: number; value: number; format?: (v: number) => string; commit?: boolean },
  onInput: (value: number) => void,
): HTMLInputElement {
  const format = options.format ?? ((v: number) => String(v));
  const input = element('input', { type: 'range', min: String(options.min), max: String(options.max), step: String(options.step), value: String(options.value) });
  const output = element('output', { textContent: format(options.value) });
  input.addEventListener('input', () => {
    output.textContent = format(Number(input.value));
    if (!options.commit) onInput(Number(input.value));
  });
  if (options.commit) input.addEventListener('change', () => onInput(Number(input.value)));
  row(parent, id, label, input).append(output);
  rangeFormats.set(input, format);
  return input;
}

/** Sets a slider made by rangeControl (and its printed value) without firing its callback. */
export function setRangeValue(input: HTMLInputElement, value: number): void {
  input.value = String(value);
  const output = input.nextElementSibling;
  if (output instanceof HTMLOutputElement) output.textContent = (rangeFormats.get(input) ?? String)(Number(input.value));
}

export function colourControl(parent: HTMLElement, id: string, label: string, hex: string, onInput: (hex: string) => void): HTMLInputElement {
  const input = element('input', { type: 'color', value: hex });
  // 'change' fires when the picker closes: one rebuild per chosen colour.
  input.addEventListener('change', () => onInput(input.value));
  row(parent, id, label, input);
  return input;
}

export function buttonControl(parent: HTMLElement, id: string, label: string, onClick: () => void): HTMLButtonElement {
  const button = element('button', { type: 'button', textContent: label });
  button.dataset.control = id;
  button.addEventListener('click', onClick);
  parent.append(button);
  return button;
}

export function checkboxControl(parent: HTMLElement, id: string, label: string, checked: boolean, onChange: (checked: boolean) => void): HTMLInputElement {
  const input = element('input', { type: 'checkbox', checked });
  input.addEventListener('change', () => onChange(input.checked));
  row(parent, id, label, input).classList.add('control-checkbox');
  return input;
}

/** Triggers a download of `bytes` as `fileName`. */
export function download(bytes: Uint8Array, fileName: string, type: string): void {
  const url = URL.createObjectURL(new Blob([bytes as Uint8Array<ArrayBuffer>], { type }));
  const link = element('a', { href: url, download: fileName });
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** sRGB hex colour (#rrggbb) <-> linear RGB, with the package's sRGB transfer functions. */
export function hexToLinear(hex: string): [number, number, number] {
  const n = Number.parseInt(hex.slice(1), 16);
  return [srgbToLinear(((n >> 16) & 255) / 255), srgbToLinear(((n >> 8) & 255) / 255), srgbToLinear((n & 255) / 255)];
}

export function linearToHex(rgb: readonly number[]): string {
  const channel = (v: number): string =>
    Math.round(linearToSrgb(Math.min(1, Math.max(0, v))) * 255)
      .toString(16)
      .padStart(2, '0');
  return `#${rgb.slice(0, 3).map(channel).join('')}`;
}
