import { NumberInput, Text } from "@mantine/core";
import type { NumValue } from "../../store/forms";

interface NumFieldProps {
  /** Visible label; without it, `ariaLabel` names the field (e.g. in a grid with column headers). */
  label?: string;
  ariaLabel?: string;
  unit: string;
  value: NumValue;
  onChange: (v: NumValue) => void;
  /** Lands on the <input> element (Mantine forwards unknown props to it). */
  testId: string;
  disabled?: boolean;
  w?: number | string;
}

/** A compact number input with its unit at the right end of the field (none when `unit` is empty). */
export function NumField({ label, ariaLabel, unit, value, onChange, testId, disabled, w }: NumFieldProps) {
  const unitWidth = unit ? Math.max(32, Math.round(unit.length * 7) + 22) : 10;
  return (
    <NumberInput
      label={label}
      aria-label={label ? undefined : ariaLabel}
      value={value}
      onChange={onChange}
      data-testid={testId}
      disabled={disabled}
      w={w}
      allowDecimal
      thousandSeparator={false}
      rightSection={
        unit ? (
          <Text size="xs" c="dimmed" pr={7} style={{ pointerEvents: "none", whiteSpace: "nowrap" }}>
            {unit}
          </Text>
        ) : null
      }
      rightSectionWidth={unitWidth}
      rightSectionPointerEvents="none"
      styles={{
        label: { fontSize: 11, color: "var(--mantine-color-gray-7)", marginBottom: 1 },
        input: { fontVariantNumeric: "tabular-nums", textAlign: "right", paddingRight: unitWidth },
      }}
      autoComplete="off"
    />
  );
}
