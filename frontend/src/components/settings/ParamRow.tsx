import { Text } from "@mantine/core";
import { memo } from "react";
import { type FieldSpec, displayUnit, rangeText, sameValue, splitCamel, validateField } from "../../lib/schema";
import { useStore } from "../../store/createStore";
import { setSetting, settingsStore } from "../../store/settings";
import { FieldInput } from "./FieldInput";

export const UNIT_DISPLAY_KEY = "UnitConversion.UnitDisplay";

/** DOM id of a field's row (the issue summary scrolls to it). */
export function rowId(axis: string, key: string): string {
  return `settings-${axis}-${key}`;
}

/** Text with `code` spans (schema descriptions quote IEC names in backticks). */
export function Ticks({ text }: { text: string }) {
  const parts = text.split("`");
  return (
    <>
      {parts.map((p, i) =>
        i % 2 === 1 ? (
          <code key={i} className="ticks">
            {p}
          </code>
        ) : (
          p
        ),
      )}
    </>
  );
}

/**
 * One parameter: label (member name split into words, and the member itself), help text from the schema
 * description with the unit and the allowed range, the input, and its problem (client check or API response).
 */
export const ParamRow = memo(function ParamRow({ axis, spec }: { axis: string; spec: FieldSpec }) {
  const value = useStore(settingsStore, (s) => s[axis]?.draft[spec.key] ?? null);
  const base = useStore(settingsStore, (s) => s[axis]?.base[spec.key] ?? null);
  const unitDisplay = useStore(settingsStore, (s) => s[axis]?.draft[UNIT_DISPLAY_KEY]);
  const issues = useStore(settingsStore, (s) => s[axis]?.issues);
  const applying = useStore(settingsStore, (s) => s[axis]?.applying ?? false);

  const clientError = validateField(spec, value);
  const mine = (issues ?? []).filter((i) => i.key === spec.key);
  const serverError = mine.map((i) => (i.code ? `${i.msg} (${i.code})` : i.msg)).join("; ");
  const error = clientError ?? (serverError || null);
  const modified = !sameValue(value, base);
  const unit = displayUnit(spec.unit, typeof unitDisplay === "string" ? unitDisplay : null);
  const range = rangeText(spec);
  const inputId = `param-input-${axis}-${spec.key}`;
  // The description often only spells out the label ("Home input signal"): then only the range is worth showing.
  const plain = (t: string) => t.toLowerCase().replace(/[^a-z0-9]/g, "");
  const help = [plain(spec.help) === plain(spec.member) ? "" : spec.help, range && `range ${range}`]
    .filter(Boolean)
    .join(" · ");

  return (
    <div
      className="param-row"
      id={rowId(axis, spec.key)}
      data-kind={spec.kind}
      data-modified={modified ? "true" : "false"}
      data-invalid={error ? "true" : "false"}
    >
      <div className="param-text" title={spec.description || undefined}>
        <label htmlFor={inputId} className="param-label">
          {splitCamel(spec.member)}
        </label>{" "}
        <span className="param-member">{spec.member}</span>
        {help && <div className="param-help">{help}</div>}
      </div>
      <div className="param-control">
        <FieldInput
          spec={spec}
          value={value}
          onChange={(v) => setSetting(axis, spec.key, v)}
          unit={unit}
          invalid={error !== null}
          testId={`param-${spec.key}`}
          id={inputId}
          disabled={applying}
        />
      </div>
      {error && (
        <Text className="param-error" size="11px" c="red.7" data-testid={`param-error-${spec.key}`} role="alert">
          {error}
        </Text>
      )}
    </div>
  );
});
